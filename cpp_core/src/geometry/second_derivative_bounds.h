// Upper bounds of a surface's second derivatives |S_uu|, |S_uv|, |S_vv| over
// a (u,v) box, from the surface's own definition rather than from samples:
// a B-spline's (or Bezier's) derivatives are B-splines whose control points
// are differences of its poles, and a B-spline lies in the convex hull of
// the control points of each knot span, so the largest of those control
// points' norms bounds the derivative over the span (rational surfaces
// through the quotient rule, below). Analytic surfaces (plane, cylinder,
// cone, sphere, torus) in closed form. With such bounds the deviation of
// the surface from a bilinear interpolation of its points is bounded, and
// with it the distance from a panel to the surface between samples
// (analysis/panel_metrics.cpp): a rigorous check that no peak of the
// deviation lies hidden between them.
#pragma once

#include <Geom_Surface.hxx>
#include <memory>
#include <vector>

#include "tessella/surface_face.h"

namespace tessella {

class SecondDerivativeBounds {
 public:
  // Null for a surface it cannot bound (offset, extrusion, revolution, ...).
  static std::unique_ptr<SecondDerivativeBounds> create(const Handle(Geom_Surface) & surface);

  // Bounds valid at every (u,v) of `box` (clamped to the surface's range; a
  // periodic direction the box leaves is bounded over its whole period).
  SecondDerivativeBound over(const UvBounds& box) const;

  // One knot span per direction and the bound over each span (row-major, v
  // fastest); an analytic surface is one span with its bound as a function
  // of the box (`analytic`).
  struct Axis {
    std::vector<double> knots;  // distinct knots, increasing
    bool periodic = false;
    // The spans [knots[i], knots[i+1]] that meet [lo, hi].
    void range(double lo, double hi, std::size_t& first, std::size_t& last) const;
  };

 private:
  SecondDerivativeBounds() = default;
  static std::unique_ptr<SecondDerivativeBounds> from_bspline(const Handle(Geom_Surface) & surface);

  Axis u_, v_;
  std::vector<SecondDerivativeBound> spans_;
  // Analytic surfaces: |S_uu| = |a + b v| at most, |S_uv| <= c, |S_vv| <= d
  // (a cone's radius grows along v); a plane is all zero.
  bool analytic_ = false;
  double radius_a_ = 0, radius_b_ = 0, mixed_ = 0, along_v_ = 0;
};

}  // namespace tessella
