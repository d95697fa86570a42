// Private helpers shared by the guide-line methods (GSM and 2G2VM, seed 004):
// curves on the surface as (u,v) polylines, their pieces inside the face, the
// initial guide curve and the scale / translate / rotate + project step.
#pragma once

#include <vector>

#include "tessella/guide_lines.h"
#include "tessella/surface_face.h"

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
};

double polyline_length(const std::vector<Vec3>& pts);
// Resampled to `count` points evenly spaced in 3D arc length.
SurfaceCurve resample(const SurfaceFace& face, const SurfaceCurve& c, int count);
// The pieces of the curve inside the trimmed face, cut at the trim.
std::vector<SurfaceCurve> inside_runs(const SurfaceFace& face, const SurfaceCurve& c);
Projection project_near(const SurfaceFace& face, const Vec3& p, const Vec2& start);
// The guide projected onto the face (cx.tol = largest allowed distance), cut to
// its longest piece on the face and extended to the boundary; throws
// InvalidParameter naming `guides`.
SurfaceCurve initial_curve(const Context& cx, const std::vector<Vec3>& guide);
// Seed 004 section 5.1 steps 4-6: c moved so that its ends land on end0 / end1.
SurfaceCurve map_curve(const Context& cx, const SurfaceCurve& c, const Vec3& end0, const Vec2& uv0,
                       const Vec3& end1, const Vec2& uv1);

}  // namespace tessella::guide_detail
