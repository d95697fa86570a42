// Declaration of the boundary-driven method (see tessella/methods.h).
#include "pipeline/declaration_builder.h"
#include "tessella/boundary_driven.h"

namespace tessella::declare {

namespace {
std::vector<int>& source_loops(BoundaryDrivenParams& p) { return p.sources.loops; }
UvPolylines& extra_curves(BoundaryDrivenParams& p) { return p.sources.extra_curves; }

// The parameters boundary_driven and curvature_lines share (one text each).
ParamDeclaration stage_decl(const std::string& name, const char* group) {
  if (name == "size")
    return decl("size", ParamKind::Real, "mm", 0.0, 1e9, "Size", "Target panel edge length",
                "Panelization", "Size");
  if (name == "skew_ratio")
    return decl("skew_ratio", ParamKind::Real, "", 0.0, 1.0, "Skew ratio (min/max angle)",
                "Triangles whose smallest / largest corner angle is under this are removed", group,
                "SkewRatio");
  if (name == "smoothing_iterations")
    return decl("smoothing_iterations", ParamKind::Integer, "", 0, 1000, "Smoothing iterations",
                "Laplacian smoothing passes (nodes stay on the surface and the trims)", group,
                "SmoothingIterations");
  if (name == "step_fraction")
    return decl("step_fraction", ParamKind::Real, "", 0.01, 0.5, "Tracing step (of the spacing)",
                "Step of the curve tracing as a fraction of the curve spacing (smaller: curves "
                "follow the field more closely, slower)",
                group, "StepFraction");
  return decl("angle_target", ParamKind::Real, "deg", 0.0, 90.0, "Angle target (0: off)",
              "After smoothing, nodes of panels with a corner under this angle are moved to "
              "open it (0 = off)",
              group, "AngleTarget");
}
}  // namespace

namespace {
MethodBuilder<BoundaryDrivenParams> builder() {
  using P = BoundaryDrivenParams;
  const char* group = "Boundary driven";
  MethodBuilder<P> b("boundary_driven", "Boundary-driven",
                     "quad mesh whose lines follow the trims (seed 001)");
  b.param(&P::size, stage_decl("size", group))
      .param(&P::rho, decl("rho", ParamKind::Real, "", 0.5, 8.0, "Rho (IDW power)",
                           "Power of the inverse distance weighting of the direction field "
                           "(higher: the nearest trim dominates)",
                           group, "Rho"))
      .param(&P::skew_ratio, stage_decl("skew_ratio", group))
      .param(&P::smoothing_iterations, stage_decl("smoothing_iterations", group))
      .param(&P::quadrangulate,
             decl("quadrangulate", ParamKind::Boolean, "", 0, 1, "Quadrangulate",
                  "Split every panel by centre and edge midpoints (all quads; curves are then "
                  "traced 2 x Size apart)",
                  group, "Quadrangulate"))
      .param(&source_loops,
             decl("source_loops", ParamKind::IntegerList, "", 0, 1e6, "Source loops",
                  "Trim loops (0 = outer, then the holes) the direction field follows; "
                  "empty = all",
                  group, "SourceLoops"))
      .param(&extra_curves,
             decl("extra_curves", ParamKind::UvCurves, "", 0, 1e4, "Extra curves",
                  "Extra curves on the face the direction field also follows (edges lying "
                  "on the surface)",
                  group, "ExtraCurves"))
      .param(&P::step_fraction, stage_decl("step_fraction", group))
      .param(&P::corner_angle_deg,
             decl("corner_angle", ParamKind::Real, "deg", 1.0, 179.0, "Corner angle",
                  "A sharper turn of a trim is a corner: a node no curve starts from", group,
                  "CornerAngle"))
      .param(&P::min_edge_fraction,
             decl("min_edge_fraction", ParamKind::Real, "", 0.0, 0.9, "Min edge fraction",
                  "Network edges shorter than this fraction of the curve spacing are collapsed",
                  group, "MinEdgeFraction"))
      .param(&P::angle_target_deg, stage_decl("angle_target", group))
      .shared("trim_deflection", &P::trim_deflection)
      .shared("max_panels", &P::max_panels);
  return b;
}

// curvature_lines: the boundary-driven stages along the principal curvature
// lines (issue 16); the trims' own field only near the trims, so no source
// loops or extra curves.
// BoundaryDrivenParams' fields as CurvatureLinesParams' (the builder binds
// fields of its own params struct).
template <class T>
T CurvatureLinesParams::*as_cl(T BoundaryDrivenParams::*field) {
  return static_cast<T CurvatureLinesParams::*>(field);
}

MethodBuilder<CurvatureLinesParams> curvature_lines_builder() {
  using P = CurvatureLinesParams;
  const char* group = "Curvature lines";
  MethodBuilder<P> b("curvature_lines", "Curvature lines",
                     "quad mesh along the principal curvature lines (for planar panels)");
  b.param(as_cl(&BoundaryDrivenParams::size), stage_decl("size", group))
      .param(as_cl(&BoundaryDrivenParams::boundary_blend),
             decl("boundary_blend", ParamKind::Real, "", 0.0, 100.0, "Boundary blend (spacings)",
                  "Within this many curve spacings of the trim the lines turn to follow the "
                  "trim (0: principal directions up to the trim)",
                  group, "BoundaryBlend"))
      .param(as_cl(&BoundaryDrivenParams::field_smoothness),
             decl("field_smoothness", ParamKind::Real, "", 1e-3, 100.0, "Field smoothness",
                  "Weight of equal neighbours in the direction field's fit (higher: smoother "
                  "lines, less exactly principal)",
                  group, "FieldSmoothness"))
      .param(as_cl(&BoundaryDrivenParams::quadrangulate),
             decl("quadrangulate", ParamKind::Boolean, "", 0, 1, "Quadrangulate",
                  "Split every panel by centre and edge midpoints (all quads; curves are then "
                  "traced 2 x Size apart)",
                  group, "Quadrangulate"))
      .param(as_cl(&BoundaryDrivenParams::smoothing_iterations),
             stage_decl("smoothing_iterations", group))
      .param(as_cl(&BoundaryDrivenParams::skew_ratio), stage_decl("skew_ratio", group))
      .param(as_cl(&BoundaryDrivenParams::step_fraction), stage_decl("step_fraction", group))
      .param(as_cl(&BoundaryDrivenParams::angle_target_deg), stage_decl("angle_target", group))
      .shared("trim_deflection", as_cl(&BoundaryDrivenParams::trim_deflection))
      .shared("max_panels", as_cl(&BoundaryDrivenParams::max_panels));
  return b;
}
}  // namespace

std::vector<MethodDeclaration> boundary_driven_methods() {
  return {builder().build(&boundary_driven), curvature_lines_builder().build(&curvature_lines)};
}

}  // namespace tessella::declare

namespace tessella {

BoundaryDrivenParams boundary_driven_params(const ParamValues& values) {
  check_param_values(method_declaration("boundary_driven"), values);
  return declare::builder().filler()(values);
}

}  // namespace tessella
