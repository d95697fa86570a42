// An upper bound of the distance from a piece of a panel model to the
// surface over a whole cell of the piece, not only at its samples: the check
// that no peak of a panel's deviation lies hidden between the samples the
// metric probed (panel_metrics.cpp; on OCCT's terrain the 8 x 8 grid of a
// border panel stepped over dips of 20 mm within 10-15 mm and reported 5.40
// where the distance reaches 10.16).
//
// For each corner x_k of the cell a surface point S(f_k) (any: a foot point
// or the surface point at the corner's own parameters). Over the cell, map
// the parameters bilinearly (a triangle: linearly) between the f_k: phi.
// The panel point x is itself bilinear (linear) over the cell, so
//   x - S(phi) = I(x - S(f)) + (I(S o phi) - S o phi),
// with I the interpolation of the corner values: the first term is at most
// the largest |x_k - S(f_k)| (the norm of a bilinear vector is convex along
// each parameter, so it peaks at a corner), the second at most
// (M_ss + M_tt) / 8 in the cell's unit coordinates (linear interpolation
// error h^2 / 8 max |f''| per direction), where S o phi's second
// derivatives come from the surface's bounds over the f_k's box
// (SurfaceFace::second_derivative_bound) and phi's edge vectors. A triangle
// gets the same form (its barycentric spread: the weighted variance of the
// corners' u is at most a quarter of their range squared). Since
// dist(x, S) <= |x - S(phi(x))|, the sum bounds the distance at every point
// of the cell.
#pragma once

#include <array>

#include "tessella/surface_face.h"

namespace tessella {

// A point of the panel model and two surface points met for it: at the
// point's own parameters q (the panel's map) and at f (its foot point where
// projected, else q again).
struct BoundCorner {
  Vec3 x;  // on the panel model
  Vec2 f;  // surface parameters
  Vec3 s;  // S(f)
  Vec2 q;
  Vec3 s_q;  // S(q)
};

// max |D^2(S o phi)[e, e]| for an edge vector e of phi whose components are
// at most (du, dv) in size, with m bounding S's second derivatives.
double along_edge(const SecondDerivativeBound& m, double du, double dv);

// Second-derivative bounds valid over a box holding the cells of a panel:
// one lookup a panel rather than one per cell for the first, cheapest try.
struct CurvatureOverBox {
  UvBounds box;
  SecondDerivativeBound m;
};

// The bound over the bilinear cell with corners c (in the order
// (0,0), (1,0), (1,1), (0,1) of its own parameters): the least of the bound
// through the feet, through the own parameters (where the feet of a cell
// jump across a crease of the distance, a bilinear map between them spans
// a wide stretch of the surface, however small the cell), and through one
// corner's surface point for all four (phi constant: no interpolation
// error, the distances to that one point). +infinity for a surface without
// second-derivative bounds. The choices are tried in that order and the
// first at most `enough` is returned (a caller that only asks whether the
// bound is below it need not pay for the rest); the feet are tried first
// with `hint` where their box lies inside its box.
double bilinear_cell_bound(const SurfaceFace& face, const std::array<BoundCorner, 4>& c,
                           double enough = -1, const CurvatureOverBox* hint = nullptr);
// The first try of bilinear_cell_bound on a face that is not periodic (its
// feet need no unwrapping), from the corners' feet f_k and the largest
// |x_k - S(f_k)|: the same value, or -1 where the feet's box leaves the
// hint's. For a caller that keeps the corners' gaps: a quad's 64 cells,
// most of which pass here, without the copies of their corners.
double bilinear_hint_bound(const std::array<Vec2, 4>& feet, double gap,
                           const CurvatureOverBox& hint);
// The same over a flat triangle.
double triangle_cell_bound(const SurfaceFace& face, const std::array<BoundCorner, 3>& c,
                           double enough = -1, const CurvatureOverBox* hint = nullptr);

}  // namespace tessella
