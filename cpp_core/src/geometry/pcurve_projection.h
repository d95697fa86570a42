// Closest points of one trim edge's curve on the surface (pcurve) to a (u,v)
// point: OCCT's Extrema_ExtPC2d set up once per edge and reused for every
// point (snap_to_trim was rebuilding the adaptor and the extrema for every
// edge of the loop at every call). Same set-up as
// Geom2dAPI_ProjectPointOnCurve(P, C, first, last), so the same answers. Not
// thread-safe.
#pragma once

#include <Extrema_ExtPC2d.hxx>
#include <Geom2dAdaptor_Curve.hxx>
#include <Geom2d_Curve.hxx>
#include <gp_Pnt2d.hxx>
#include <vector>

namespace tessella {

class PcurveProjection {
 public:
  PcurveProjection(const Handle(Geom2d_Curve) & curve, double first, double last);
  PcurveProjection(const PcurveProjection&) = delete;
  PcurveProjection& operator=(const PcurveProjection&) = delete;

  // The curve's end points, then its extrema of the distance to p (OCCT's order).
  void candidates(const gp_Pnt2d& p, std::vector<gp_Pnt2d>& out);
  // No candidate lies nearer to p than this (the distance to a box around
  // the curve's control points or segment, slightly grown; 0 for a curve
  // of another kind): a caller after the nearest can skip the curve.
  double lower_bound(const gp_Pnt2d& p) const;

 private:
  Handle(Geom2d_Curve) curve_;
  double first_, last_;
  Geom2dAdaptor_Curve adaptor_;
  Extrema_ExtPC2d extrema_;
  bool has_box_ = false;
  double box_[4] = {0, 0, 0, 0};  // x min, x max, y min, y max
};

}  // namespace tessella
