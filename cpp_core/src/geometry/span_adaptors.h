// Span-cached evaluation of a surface over many spans: OCCT's
// GeomAdaptor_Surface keeps the polynomial of one B-spline span, so a panel
// spanning several spans of a big surface (a 312 x 323-pole terrain) rebuilt
// it at almost every sample. Here one adaptor per span, in a small
// direct-mapped table (8 x 8 neighbouring spans stay cached together). Each
// adaptor evaluates exactly as a lone GeomAdaptor_Surface does, so the
// results do not depend on which adaptor answered. Not thread-safe.
#pragma once

#include <GeomAdaptor_Surface.hxx>
#include <Geom_Surface.hxx>
#include <array>
#include <memory>
#include <vector>

namespace tessella {

class SpanAdaptors {
 public:
  explicit SpanAdaptors(const Handle(Geom_Surface) & surface);
  SpanAdaptors(const SpanAdaptors&) = delete;
  SpanAdaptors& operator=(const SpanAdaptors&) = delete;

  // The adaptor to evaluate (u, v) with.
  GeomAdaptor_Surface& at(double u, double v);

 private:
  static constexpr int kSide = 8;
  // Index of the knot interval holding t (clamped), and its bounds.
  static int locate(const std::vector<double>& knots, double t, double& lo, double& hi);

  Handle(Geom_Surface) surface_;
  std::vector<double> u_knots_, v_knots_;  // distinct knots; empty: one adaptor
  std::array<std::unique_ptr<GeomAdaptor_Surface>, kSide * kSide> slots_;
  // The last span located, to skip the search for the next nearby point.
  double u_lo_ = 1, u_hi_ = 0, v_lo_ = 1, v_hi_ = 0;
  int last_ = 0;
};

}  // namespace tessella
