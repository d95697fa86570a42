// Private helpers shared by the guide-line methods (GSM and 2G2VM, seed 004):
// curves on the surface as (u,v) polylines, their pieces inside the face, the
// initial guide curve and the scale / translate / rotate + project step.
#pragma once

#include <utility>
#include <vector>

#include "methods/guide_lines/chord_division.h"
#include "methods/guide_lines/right_angle_rule.h"
#include "tessella/guide_line_scaling.h"
#include "tessella/two_guide_lines.h"
#include "tessella/surface_face.h"

namespace tessella::guide_detail {

// The outer trim loop (closed; first point not repeated).
struct Boundary {
  std::vector<Vec3> xyz;
  std::vector<Vec2> uv;
};

// Point-in-face test on the cached (u,v) trim polylines (even-odd crossings of
// a ray along +u, edges bucketed in bands of v): ~20x faster than OCCT's
// classifier, which was a quarter of the GSM time. The polylines stay within
// the trim deflection of the true trim. When the polylines do not classify a
// few probe points well away from the trim as OCCT does (e.g. loops that do
// not close in (u,v) on periodic faces), every query falls back to
// SurfaceFace::is_inside.
class UvInside {
 public:
  UvInside() = default;
  UvInside(const SurfaceFace& face, const std::vector<TrimLoop>& loops);
  bool operator()(double u, double v) const;
  // OCCT's classifier (exact trim, slower); for the final boundary crossings.
  bool exact(double u, double v) const { return face_ != nullptr && face_->is_inside(u, v); }
  bool fast() const { return !fallback_; }

 private:
  bool crossings_odd(double u, double v) const;
  const SurfaceFace* face_ = nullptr;
  bool fallback_ = true;
  double v0_ = 0, dv_ = 1, eps_ = 0;
  std::vector<std::pair<Vec2, Vec2>> edges_;
  std::vector<std::vector<int>> bands_;
};

struct Context {
  const SurfaceFace& face;
  Boundary boundary;
  double l1 = 0, advance = 0, tol = 0;
  int samples = 0;  // points per curve
  UvInside inside;  // set from face.trim_loops after construction
};

double polyline_length(const std::vector<Vec3>& pts);
// Resampled to `count` points evenly spaced in 3D arc length.
SurfaceCurve resample(const SurfaceFace& face, const SurfaceCurve& c, int count);
// The pieces of the curve inside the trimmed face, cut at the trim (exact:
// on the true trim, with OCCT's classifier; else on the trim polylines, ~10x
// faster, for callers that snap the ends themselves).
std::vector<SurfaceCurve> inside_runs(const Context& cx, const SurfaceCurve& c,
                                      bool exact = true);
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
