// A B-spline surface closed on itself but not periodic: its first and last
// rows of poles (and weights) along u, or along v, are the same, so its two
// sides there are one curve in space, yet OCCT calls it not periodic (a
// STEP file's surfaces carry no periodic flag; OCCT's Pump_TopCover.brep
// has such a face). Every method then read the seam as two sides of the
// face: boundary_driven traced curves from both (a seam with a pole at an
// end kept T-junctions), the grids put a node on each. Read as periodic it
// is meshed across its seam like a cylinder.
#pragma once

#include <Geom_BSplineSurface.hxx>

namespace tessella {

// The surface made periodic (on a copy) along each direction in which it is
// closed on itself, or the surface itself where it is not. A copy is taken
// only if it evaluates to the same points: a 17 x 17 grid over the surface's
// range and its four sides, within 1e-12 of the poles' extent (OCCT's
// SetUPeriodic keeps the knots between the ends and drops the last row, so
// for a clamped surface with equal end rows nothing moves; anything else is
// left as it was).
Handle(Geom_BSplineSurface) periodic_where_closed(const Handle(Geom_BSplineSurface) & surface);

}  // namespace tessella
