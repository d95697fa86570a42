// curvature_lines (issue 16): the direction field of the principal curvature
// lines, for the boundary-driven tracer. Quads whose sides follow a conjugate
// network can be made planar while staying on the surface (Liu et al. 2006;
// Zadravec, Schiftner, Wallner 2010); the principal network is the natural
// conjugate one, and the only orthogonal one.
//
// At each node of the field grid the principal direction comes from the
// shape operator (second fundamental form in an orthonormal tangent frame),
// as a cross (cos 4 theta, sin 4 theta) like the BDTensor. The field is the
// smooth least-squares fit of
//   - the principal crosses, weighted by D / (D + D_ref), D = |k1 - k2| (the
//     directions are undefined where the surface is umbilic or flat: there
//     the smoothing carries the field across from where they are defined,
//     rather than scattering singularities over noise),
//   - the trims' field (the BDTensor), weighted by exp(-(d / blend)^2) at
//     distance d from the trim (so boundary panels stay regular), and a little
//     everywhere (where no principal direction exists anywhere, a sphere, the
//     trims decide),
//   - equal neighbours (weight `smoothness` per grid edge),
// solved by Jacobi sweeps (deterministic).
#pragma once

#include "methods/boundary_driven/bd_tensor.h"

namespace tessella {

struct PrincipalFieldParams {
  double blend_distance = 0.0;  // mm from the trim over which the trims' field takes over; >= 0
  double smoothness = 0.25;     // weight of a grid edge against a fully defined direction
  int sweeps = 200;             // Jacobi sweeps of the fit
};

// On the nu x nv grid over the face's (u,v) bounds (as sample_bd_tensor).
BdTensorGrid principal_curvature_field(const SurfaceFace& face, const BdTensor& trims, int nu,
                                       int nv, const PrincipalFieldParams& params);

// The principal directions' cross at (u,v) before any fit: (cos 4 theta,
// sin 4 theta) of the first principal direction against the unit du frame,
// and D = |k1 - k2| (1/mm). Second derivatives by central differences of
// the first (one-sided at the face's bounds).
Vec2 principal_cross(const SurfaceFace& face, const Vec2& uv, double& anisotropy);

}  // namespace tessella
