"""The only importer of the compiled module `_core` (built by CMake into this folder).

What Python calls: `panelize` (the whole pipeline, once per face) and
`method_declarations` (THE declaration of methods and parameters); the
fabrication entry points (unfold, flatten, nest, offsets, shape export); and a
small stage-level console API for plots and benchmarks: the guide-line curve
sets (`guide_line_scaling_curves`, `two_guide_lines_curves` with their params
structs), `boundary_driven_stages` (traced curves and the preliminary network),
`iso_grid` + `measure_panels` (the coarsest-grid search of
bench/compare_methods.py), `summarize`, `surface_evaluations`, `global_projections`, `mesh_folds`,
`fold_angle_deg`; `panel_types` / `flat_panel_types` / `mesh_panel_types` (congruent flat panels);
`panel_families` / `panel_distance` (panels within a tolerance of a template).
"""

try:
    from . import _core  # noqa: F401
except ImportError as exc:  # pragma: no cover - message for a user without a build
    raise ImportError(
        "Tessella's compiled core is missing: run 'make build' in the repository "
        "(it builds freecad_workbench/_core*.so with /usr/bin/python3). "
        f"Original error: {exc}"
    ) from exc

from ._core import (  # noqa: E402,F401
    Cancelled,
    method_declarations,
    panelize,
    panelize_faces,
    FaceSet,
    FaceSetResult,
    PanelizeResult,
    BoundaryDrivenParams,
    FlattenParams,
    flatten_panels,
    flatten_face_set_panels,
    NestParams,
    PanelTypeParams,
    PanelFamilyParams,
    panel_families,
    PanelClassParams,
    classify_panels,
    classify_mesh_panels,
    panel_distance,
    flat_panel_types,
    mesh_panel_types,
    panel_types,
    OutlineOffsetParams,
    UnfoldParams,
    fold_angle_deg,
    nest_parts,
    offset_outline,
    unfold_panels,
    GuideLineScalingParams,
    IsoGridParams,
    MetricsParams,
    PanelMesh,
    SurfaceFace,
    boundary_driven_stages,
    boundary_driven_params,
    TwoGuideLinesParams,
    guide_line_scaling_curves,
    iso_grid,
    measure_panels,
    mesh_folds,
    nodes_to_brep,
    panel_faces,
    panels_to_brep,
    rods_to_brep,
    summarize,
    two_guide_lines_curves,
    surface_evaluations,
    global_projections,
)
