#include "faceset/guides_along_cuts.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

#include "geometry/segment_closest.h"
#include "geometry/trim_deflection.h"

namespace tessella {

namespace {

// A guide within this share of the rod of a trim is meant to be the cut.
constexpr double kAlongShare = 0.01;
// Guide points at most this share of the rod apart, so that between two
// points moved onto a curved trim the straight step stays on it.
constexpr double kStepShare = 1.0 / 16.0;

struct Segment {
  Vec3 a, d;  // from a, a + d
};

// The segments near a point: a uniform voxel grid, each segment in every
// voxel its box (grown by the reach) meets, in segment order.
class SegmentVoxels {
 public:
  SegmentVoxels(const std::vector<Segment>& segments, double reach, double voxel) : h_(voxel) {
    for (std::size_t s = 0; s < segments.size(); ++s) {
      const Vec3 lo = segments[s].a.cwiseMin(segments[s].a + segments[s].d).array() - reach;
      const Vec3 hi = segments[s].a.cwiseMax(segments[s].a + segments[s].d).array() + reach;
      for (long x = cell(lo.x()); x <= cell(hi.x()); ++x)
        for (long y = cell(lo.y()); y <= cell(hi.y()); ++y)
          for (long z = cell(lo.z()); z <= cell(hi.z()); ++z)
            voxels_[key(x, y, z)].push_back(static_cast<int>(s));
    }
  }
  const std::vector<int>& at(const Vec3& p) const {
    static const std::vector<int> none;
    const auto it = voxels_.find(key(cell(p.x()), cell(p.y()), cell(p.z())));
    return it == voxels_.end() ? none : it->second;
  }

 private:
  long cell(double x) const { return static_cast<long>(std::floor(x / h_)); }
  static std::uint64_t key(long x, long y, long z) {
    // 21 bits a coordinate: voxels of a model up to 2 million voxels across.
    auto b = [](long v) { return static_cast<std::uint64_t>(v) & 0x1FFFFFu; };
    return (b(x) << 42) | (b(y) << 21) | b(z);
  }
  double h_;
  std::unordered_map<std::uint64_t, std::vector<int>> voxels_;
};

}  // namespace

Polylines guides_along_cuts(const std::vector<const SurfaceFace*>& faces, const Polylines& guides,
                            double size, double trim_deflection_mm) {
  if (guides.empty() || !(size > 0)) return guides;
  std::vector<Segment> segments;
  double length = 0;
  for (const SurfaceFace* face : faces) {
    for (const TrimLoop& loop : face->trim_loops(trim_deflection(*face, trim_deflection_mm))) {
      const std::size_t n = loop.xyz.size();
      for (std::size_t k = 0; n >= 2 && k < n; ++k) {  // closed: n - 1 back to 0 too
        const Vec3& a = loop.xyz[k];
        const Vec3& b = loop.xyz[(k + 1) % n];
        segments.push_back({a, b - a});
        length += (b - a).norm();
      }
    }
  }
  if (segments.empty()) return guides;
  const double reach = kAlongShare * size;
  // Voxels about a segment long (a few segments each), never under the reach.
  const SegmentVoxels voxels(segments, reach,
                             std::max(reach, 2.0 * length / double(segments.size())));
  const double step = kStepShare * size;
  Polylines out;
  for (const std::vector<Vec3>& guide : guides) {
    std::vector<Vec3> dense;
    for (std::size_t k = 0; k < guide.size(); ++k) {
      if (k > 0) {
        const Vec3 d = guide[k] - guide[k - 1];
        const int pieces = static_cast<int>(std::ceil(d.norm() / step));
        for (int q = 1; q < pieces; ++q) dense.push_back(guide[k - 1] + d * (double(q) / pieces));
      }
      dense.push_back(guide[k]);
    }
    for (Vec3& p : dense) {
      double best = reach;
      Vec3 to = p;
      for (int s : voxels.at(p)) {
        const Segment& e = segments[std::size_t(s)];
        const Vec3 q = e.a + closest_fraction(e.a, e.d, p) * e.d;
        const double d = (q - p).norm();
        if (d < best) best = d, to = q;
      }
      p = to;
    }
    out.push_back(std::move(dense));
  }
  return out;
}

}  // namespace tessella
