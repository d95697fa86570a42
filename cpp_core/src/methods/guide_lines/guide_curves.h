// Private helpers shared by the guide-line methods (GSM and 2G2VM, seed 004):
// curves on the surface as (u,v) polylines, their pieces inside the face, the
// initial guide curve and the scale / translate / rotate + project step.
#pragma once

#include <utility>
#include <vector>

#include "geometry/uv_trim_classifier.h"
#include "methods/guide_lines/chord_division.h"
#include "methods/guide_lines/right_angle_rule.h"
#include "tessella/guide_line_scaling.h"
#include "tessella/surface_face.h"
#include "tessella/two_guide_lines.h"

namespace tessella::guide_detail {

// The outer trim loop (closed; first point not repeated).
struct Boundary {
  std::vector<Vec3> xyz;
  std::vector<Vec2> uv;
};

struct Context {
  const SurfaceFace& face;
  Boundary boundary;
  double l1 = 0, advance = 0, tol = 0;
  int samples = 0;  // points per curve
  // The trim polylines' classifier, cross-checked against OCCT (set from
  // face.trim_loops after construction; OCCT's exact test is face.is_inside).
  UvTrimClassifier inside;
  // GSM: a new curve's ends lie `step` from the curve along the boundary
  // (else seed 004's line through D'); set from the params.
  bool ends_by_distance = true;
};

double polyline_length(const std::vector<Vec3>& pts);
// Distance from x to the polyline.
double distance_to_polyline(const std::vector<Vec3>& pts, const Vec3& x);
// The point of a closed polyline (last point joined to the first) nearest to
// x: segment `seg` from point seg to point seg + 1, at parameter t on it.
struct LoopPoint {
  std::size_t seg = 0;
  double t = 0.0;
  double distance = 0.0;
};
LoopPoint nearest_on_loop(const std::vector<Vec3>& loop, const Vec3& x);
// The trim crossing between an inside and an outside (u,v) point (bisection;
// exact: the last steps on OCCT's classifier, so the point is on the true trim).
Vec2 bisect_boundary(const Context& cx, Vec2 in, Vec2 out, bool exact = true);
// Resampled to `count` points evenly spaced in 3D arc length.
SurfaceCurve resample(const SurfaceFace& face, const SurfaceCurve& c, int count);
// The pieces of the curve inside the trimmed face, cut at the trim (exact:
// on the true trim, with OCCT's classifier; else on the trim polylines, ~10x
// faster, for callers that snap the ends themselves).
std::vector<SurfaceCurve> inside_runs(const Context& cx, const SurfaceCurve& c, bool exact = true);
Projection project_near(const SurfaceFace& face, const Vec3& p, const Vec2& start);
// The guide projected onto the face (cx.tol = largest allowed distance), cut to
// its longest piece on the face and extended to the boundary; throws
// InvalidParameter naming `guides`.
SurfaceCurve initial_curve(const Context& cx, const std::vector<Vec3>& guide);
// Seed 004 section 5.1 steps 4-6: c moved so that its ends land on end0 / end1.
// Each moved point starts its projection from the matching point of `near`
// (c when null; a curve with as many points as c).
SurfaceCurve map_curve(const Context& cx, const SurfaceCurve& c, const Vec3& end0, const Vec2& uv0,
                       const Vec3& end1, const Vec2& uv1, const SurfaceCurve* near = nullptr);
// c moved by the similarity of the (u,v) plane that takes its ends to uv0 /
// uv1 (same point count, exactly on the surface, no projection needed).
SurfaceCurve map_curve_uv(const SurfaceFace& face, const SurfaceCurve& c, const Vec2& uv0,
                          const Vec2& uv1);

}  // namespace tessella::guide_detail
