// A 3D polyline (an edge sampled finely) with boxes round runs of its
// segments, for "is this point within d of the edge" asked of many points
// (every trim point of a face, every boundary vertex of a mesh).
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "tessella/vec.h"

namespace tessella {

class EdgeTrack {
 public:
  EdgeTrack() = default;
  explicit EdgeTrack(std::vector<Vec3> points);
  // Whether p lies within d of the polyline.
  bool near(const Vec3& p, double d) const;
  // The segment nearest to p if it lies within d (segment index and the
  // fraction along it); false if none does.
  bool nearest(const Vec3& p, double d, std::size_t& segment, double& t) const;
  const std::vector<Vec3>& points() const { return points_; }

 private:
  static constexpr std::size_t kRun = 32;  // segments per box
  std::vector<Vec3> points_;
  std::vector<Vec3> lo_, hi_;  // per run of kRun segments
};

// The first of `tracks` that p lies within d of (-1: none).
int first_track_near(const std::vector<EdgeTrack>& tracks, const Vec3& p, double d);

// A curve `at`(t), t in [first, last], as a polyline at uniform parameters:
// 64 chords, doubled (the midpoints kept) until no chord's midpoint lies
// farther than max_sag from the chord, or up to max_chords. `sag`: the
// largest such distance on the polyline returned.
std::vector<Vec3> sample_curve(const std::function<Vec3(double)>& at, double first, double last,
                               double max_sag, int max_chords, double& sag);

}  // namespace tessella
