#include "analysis/known_surface_points.h"

#include <algorithm>
#include <cmath>

namespace tessella {

namespace {
constexpr int kMaxCells = 16;  // per axis
}

void KnownSurfacePoints::reset(const Vec3& lo, const Vec3& hi) {
  origin_ = lo;
  const Vec3 extent = (hi - lo).cwiseMax(0.0);
  const double side = extent.maxCoeff();
  const double cell = side / kMaxCells;
  inv_cell_ = cell > 0 && std::isfinite(cell) ? 1.0 / cell : 0.0;
  for (int a = 0; a < 3; ++a)
    n_[a] = inv_cell_ > 0 ? std::clamp(int(std::ceil(extent[a] * inv_cell_)), 1, kMaxCells) : 1;
  const std::size_t cells = std::size_t(n_[0]) * n_[1] * n_[2];
  head_.assign(cells, -1);
  // Read only where a cell has points, so set by add() alone.
  if (cell_lo_.size() < cells) cell_lo_.resize(cells), cell_hi_.resize(cells);
  next_.clear();
  uv_.clear();
  xyz_.clear();
  // A panel meets a few dozen points, a boundary panel hundreds.
  next_.reserve(64);
  uv_.reserve(64);
  xyz_.reserve(64);
}

namespace {
// The clamped floor of the coordinate in cells, monotone: a point inside a
// query box lands in the box's cell range even when it lies outside the
// grid's box. (For f >= 0, int(f) is floor(f); NaN goes to cell 0.)
inline int clamped_cell(double f, int n) { return f >= n - 1 ? n - 1 : (f > 0 ? int(f) : 0); }
}  // namespace

void KnownSurfacePoints::cell_range(const Vec3& lo, const Vec3& hi, int first[3],
                                    int last[3]) const {
  for (int a = 0; a < 3; ++a) {
    first[a] = clamped_cell((lo[a] - origin_[a]) * inv_cell_, n_[a]);
    last[a] = clamped_cell((hi[a] - origin_[a]) * inv_cell_, n_[a]);
    if (!(lo[a] <= hi[a])) first[a] = 0, last[a] = n_[a] - 1;  // NaN: the whole axis
  }
}

int KnownSurfacePoints::cell_of(const Vec3& p) const {
  const int i = clamped_cell((p.x() - origin_.x()) * inv_cell_, n_[0]);
  const int j = clamped_cell((p.y() - origin_.y()) * inv_cell_, n_[1]);
  const int k = clamped_cell((p.z() - origin_.z()) * inv_cell_, n_[2]);
  return (k * n_[1] + j) * n_[0] + i;
}

void KnownSurfacePoints::add(const Vec2& uv, const Vec3& xyz) {
  const std::size_t c = std::size_t(cell_of(xyz));
  if (head_[c] < 0) {
    cell_lo_[c] = cell_hi_[c] = xyz;
  } else {
    cell_lo_[c] = cell_lo_[c].cwiseMin(xyz);
    cell_hi_[c] = cell_hi_[c].cwiseMax(xyz);
  }
  next_.push_back(head_[c]);
  head_[c] = static_cast<int>(xyz_.size());
  uv_.push_back(uv);
  xyz_.push_back(xyz);
}

std::size_t KnownSurfacePoints::nearer(const Vec3& x, double& d_near, double tiny,
                                       std::size_t from) const {
  const std::size_t none = xyz_.size();
  if (!(d_near > tiny) || from >= none) return none;  // nothing can be nearer by more than tiny
  // Only a point with |p - x| + tiny < d_near (as given) can ever be taken:
  // those lie in the ball of radius d_near around x.
  int first[3], last[3];
  if (std::isfinite(d_near)) {
    const Vec3 r = Vec3::Constant(d_near);
    cell_range(x - r, x + r, first, last);
  } else {
    for (int a = 0; a < 3; ++a) first[a] = 0, last[a] = n_[a] - 1;
  }
  candidates_.clear();
  const double limit = d_near;
  // A cheap pre-test on squared distances, loose enough (1e-12) that no
  // point the exact test takes is dropped.
  const double limit2 = limit * limit * (1 + 1e-12);
  for (int k = first[2]; k <= last[2]; ++k)
    for (int j = first[1]; j <= last[1]; ++j)
      for (int i = first[0]; i <= last[0]; ++i) {
        const std::size_t c = std::size_t((k * n_[1] + j) * n_[0] + i);
        if (head_[c] < 0 || std::size_t(head_[c]) < from) continue;
        // Every point of the cell is at least as far as its box, and the
        // rounded differences keep that order: a box beyond the pre-test's
        // limit holds no point the scan could take.
        const Vec3 gap = (cell_lo_[c] - x).cwiseMax(x - cell_hi_[c]).cwiseMax(0.0);
        if (gap.squaredNorm() > limit2) continue;
        // A cell's list runs from its newest point back: stop below `from`.
        for (int p = head_[c]; p >= 0 && std::size_t(p) >= from; p = next_[std::size_t(p)])
          if ((xyz_[std::size_t(p)] - x).squaredNorm() <= limit2 &&
              (xyz_[std::size_t(p)] - x).norm() + tiny < limit)
            candidates_.push_back(p);
      }
  if (candidates_.empty()) return none;
  // The scan's rule, in the order the points were added.
  std::sort(candidates_.begin(), candidates_.end());
  std::size_t near = none;
  for (int p : candidates_) {
    const double d = (xyz_[std::size_t(p)] - x).norm();
    if (d + tiny < d_near) d_near = d, near = std::size_t(p);
  }
  return near;
}

}  // namespace tessella
