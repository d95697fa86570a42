// Boundary-driven meshing, stage 2: the BDTensor (seed 001 section 2.1), a field
// of two conjugate directions interpolated by inverse distance weighting
// (eq. 1-2, power rho) from samples on the source curves.
//
// Each sample carries the source's tangent t_i; its conjugate is n x t_i (the
// perpendicular in the tangent plane). At an evaluation point the sample
// tangents are expressed in the local frame (e1 = unit du, e2 = n x e1, z = n)
// as angles theta_i; since {t, n x t, -t, -n x t} is the same pair of
// directions, the weighted mean is taken of (cos 4 theta_i, sin 4 theta_i) and
// theta = atan2 / 4 (a sign or a quarter turn of a source does not change the
// field). d(x, x_i) is the 3D distance.
#pragma once

#include <vector>

#include "methods/boundary_driven/bd_sources.h"

namespace tessella {

struct BdTensorParams {
  double rho = 2.0;             // IDW power, [0.5, 8]
  double sample_spacing = 0.0;  // mm between samples along a source; > 0
};

struct BdTensorSample {
  Vec2 uv;
  Vec3 point;
  Vec3 tangent;  // unit, in the tangent plane
};

struct BdTensor {
  std::vector<BdTensorSample> samples;
  double rho = 2.0;
};

BdTensor build_bd_tensor(const SurfaceFace& face, const std::vector<BdPolyline>& sources,
                         const BdTensorParams& params);

struct BdDirections {
  Vec3 normal;
  Vec3 d1, d2;    // unit 3D directions, d2 = normal x d1
  Vec2 uv1, uv2;  // the same directions in (u,v) per mm of 3D length
};

BdDirections eval_bd_tensor(const BdTensor& tensor, const SurfaceFace& face, const Vec2& uv);

// The field sampled on a regular (u,v) grid over the face's bounds: eq. 1-2 are
// evaluated once per grid node (the doubled-angle vector (cos 4 theta,
// sin 4 theta) relative to the unit-du frame), then interpolated bilinearly.
// Tracing calls the field thousands of times; this makes a call O(1) instead
// of O(samples).
struct BdTensorGrid {
  Vec2 lo, step;
  int nu = 0, nv = 0;
  std::vector<Vec2> c4s4;  // nu * nv, row-major in u
};
BdTensorGrid sample_bd_tensor(const BdTensor& tensor, const SurfaceFace& face, int nu, int nv);
BdDirections eval_bd_tensor(const BdTensorGrid& grid, const SurfaceFace& face, const Vec2& uv);

// (u,v) change per mm of 3D motion along the tangent direction d at a point with
// derivatives du, dv (least squares of [du dv] x = d).
Vec2 tangent_to_uv(const Vec3& du, const Vec3& dv, const Vec3& d);

}  // namespace tessella
