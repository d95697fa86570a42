"""The only importer of the compiled module `_core` (built by CMake into this folder)."""

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
    BoundaryDrivenParams,
    EqualSizeGridParams,
    FlattenParams,
    flatten_panels,
    NestParams,
    OutlineOffsetParams,
    UnfoldParams,
    fold_angle_deg,
    nest_parts,
    offset_outline,
    unfold_panel,
    unfold_panels,
    GradientDescentParams,
    GridClipParams,
    GuideLineDiamondParams,
    GuideLineScalingParams,
    IrregularParams,
    IsoGridParams,
    MetricsParams,
    PanelMesh,
    RelaxedGridParams,
    RelaxedGridReport,
    SurfaceFace,
    boundary_driven,
    boundary_driven_stages,
    TwoGuideLinesParams,
    guide_line_diamond,
    equal_size_grid,
    guide_line_scaling,
    guide_line_scaling_curves,
    WalkingAgentParams,
    WalkingAgentReport,
    equal_size_grid,
    gradient_descent,
    irregular_panels,
    is_valid_agent_start,
    iso_grid,
    measure_panels,
    mesh_folds,
    node_data,
    nodes_to_brep,
    panels_to_brep,
    relaxed_grid,
    relaxed_grid_report,
    reset_surface_evaluations,
    rods_to_brep,
    summarize,
    two_guide_lines,
    two_guide_lines_curves,
    surface_evaluations,
    walking_agent,
    walking_agent_report,
)
