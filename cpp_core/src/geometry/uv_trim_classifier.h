// The one point-in-trim test of the core: where a (u,v) point lies relative to
// the face's trim polylines (SurfaceFace::trim_loops), built once, answered in
// the hot loops of every method.
//
// Semantics (fixed, whatever the caller):
// - OnTrim: the point is within `on_trim` (a distance in (u,v)) of a polyline
//   edge, vertices included (distance <= on_trim, so with on_trim = 0 a point
//   exactly on an edge is OnTrim too);
// - otherwise Inside / Outside by the even-odd rule over all loops: a ray from
//   the point along +u counts the edges whose v-range is half-open [min, max)
//   around the point's v, so a ray through a polyline vertex counts it once
//   (or twice at a v-extremum, which does not change the parity).
// - contains() is "not Outside": a point on the trim counts as inside, as for
//   OCCT's classifier (SurfaceFace::is_inside, where ON is not OUT).
// The answer depends on the loops and on_trim only, not on the bucketing, and
// is the same on every run.
//
// The default on_trim is 1e-9 of the diagonal of the loops' (u,v) bounding box
// (the tolerance OCCT's classifier gets in SurfaceFace): it absorbs rounding,
// not the trim deflection.
//
// The polylines stand for the true trim within the trim deflection. Optionally
// (Options::check_with) the classifier is cross-checked against OCCT's on a
// 9 x 9 grid of probe points over the face's (u,v) bounds well away from the
// polylines; when one disagrees (e.g. loops that do not close in (u,v) on a
// periodic face) every contains()/classify() asks SurfaceFace::is_inside
// instead (then OnTrim is never answered).
//
// Speed: the edges are bucketed in bands of v (for classify and the scanlines
// of fixed v) and of u (for the scanlines of fixed u); a query visits the
// edges of one band.
#pragma once

#include <array>
#include <vector>

#include "tessella/surface_face.h"
#include "tessella/vec.h"

namespace tessella {

enum class TrimSide { Outside, OnTrim, Inside };

class UvTrimClassifier {
 public:
  struct Options {
    // Distance in (u,v) under which a point is OnTrim; < 0: the default
    // (1e-9 x the diagonal of the loops' (u,v) bounding box).
    double on_trim = -1;
    // When set, the cross-check against this face's OCCT classifier described
    // above (the face must outlive the classifier).
    const SurfaceFace* check_with = nullptr;
  };

  // No loops: every point is Outside.
  UvTrimClassifier() = default;
  UvTrimClassifier(const std::vector<std::vector<Vec2>>& loops, const Options& options);
  explicit UvTrimClassifier(const std::vector<std::vector<Vec2>>& loops)
      : UvTrimClassifier(loops, Options{}) {}
  UvTrimClassifier(const std::vector<TrimLoop>& loops, const Options& options);
  explicit UvTrimClassifier(const std::vector<TrimLoop>& loops)
      : UvTrimClassifier(loops, Options{}) {}

  TrimSide classify(const Vec2& p) const;
  bool contains(const Vec2& p) const { return classify(p) != TrimSide::Outside; }
  bool contains(double u, double v) const { return contains(Vec2(u, v)); }

  // Sorted crossings of the line {coordinate `free_dir` free, the other = c}
  // (free_dir 0: the line v = c, the u of its crossings; 1: u = c, the v) with
  // the polyline edges, by the same half-open rule: a point s of the line with
  // an odd number of crossings below it is inside (off the trim).
  std::vector<double> crossings(int free_dir, double c) const;

  double on_trim() const { return on_trim_; }
  bool empty() const { return edges_.empty(); }
  // True when the OCCT cross-check failed and queries go to the face.
  bool uses_occt() const { return occt_ != nullptr; }

 private:
  struct Bands {
    double lo = 0, step = 1;
    std::vector<std::vector<int>> edges;
    int index(double x) const;
  };
  void build(const Options& options);
  TrimSide classify_polylines(const Vec2& p) const;

  std::vector<std::array<Vec2, 2>> edges_;
  Vec2 lo_ = Vec2::Zero(), hi_ = Vec2::Zero();  // bounding box of the edges
  double on_trim_ = 0;
  std::array<Bands, 2> bands_;  // [d]: the edges by their range of coordinate d (0 = u, 1 = v)
  const SurfaceFace* occt_ = nullptr;
};

}  // namespace tessella
