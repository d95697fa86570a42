#include "faceset/smooth_groups.h"

#include <Geom2d_Curve.hxx>
#include <algorithm>
#include <cmath>
#include <utility>

#include "tessella/surface_face.h"

namespace tessella {

namespace {

constexpr double kPi = 3.14159265358979323846;

Vec3 edge_point(const SharedEdge& e, const SurfaceFace& face, double t) {
  const gp_Pnt2d q = e.pcurve[0]->Value(t);
  return face.point(q.X(), q.Y());
}

}  // namespace

bool meets_tangentially(const SharedEdge& e, const SurfaceFace& a, const SurfaceFace& b) {
  const double cos_limit = std::cos(kSmoothAngleDeg * kPi / 180.0);
  int checked = 0;
  for (int k = 0; k <= 8; ++k) {
    const double t = e.first + (e.last - e.first) * k / 8.0;
    const gp_Pnt2d qa = e.pcurve[0]->Value(t), qb = e.pcurve[1]->Value(t);
    const Vec3 na = a.normal(qa.X(), qa.Y()), nb = b.normal(qb.X(), qb.Y());
    if (!na.allFinite() || !nb.allFinite() || na.norm() < 0.5 || nb.norm() < 0.5) continue;
    if (std::abs(na.dot(nb)) < cos_limit) return false;
    ++checked;
  }
  return checked > 0;
}

SmoothLayout smooth_layout(const FaceSet::Impl& set, const std::vector<char>& eligible,
                           const std::vector<double>& tolerance) {
  const std::size_t n = set.faces.size();
  SmoothLayout out;
  out.group.assign(n, -1);
  std::vector<std::vector<int>> next(n);
  for (const SharedEdge& e : set.shared) {
    const int a = e.faces[0], b = e.faces[1];
    if (a == b || !eligible[static_cast<std::size_t>(a)] || !eligible[static_cast<std::size_t>(b)])
      continue;
    const SurfaceFace& fa = *set.faces[static_cast<std::size_t>(a)];
    const SurfaceFace& fb = *set.faces[static_cast<std::size_t>(b)];
    if (!meets_tangentially(e, fa, fb)) continue;
    const double sag = 0.25 * std::min(tolerance[static_cast<std::size_t>(a)],
                                       tolerance[static_cast<std::size_t>(b)]);
    double found = 0;
    std::vector<Vec3> line = sample_curve([&](double t) { return edge_point(e, fa, t); }, e.first,
                                          e.last, sag, 8192, found);
    out.edges.push_back({e.faces, EdgeTrack(std::move(line))});
    next[static_cast<std::size_t>(a)].push_back(b);
    next[static_cast<std::size_t>(b)].push_back(a);
  }
  // Groups: connected by smooth edges, numbered from the largest face's.
  std::vector<std::size_t> order(n);
  for (std::size_t f = 0; f < n; ++f) order[f] = f;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    return set.faces[x]->area() > set.faces[y]->area();
  });
  int groups = 0;
  for (std::size_t root : order) {
    if (out.group[root] >= 0 || next[root].empty()) continue;
    const int g = groups++;
    std::vector<std::size_t> stack{root};
    out.group[root] = g;
    while (!stack.empty()) {
      const std::size_t f = stack.back();
      stack.pop_back();
      for (int o : next[f])
        if (out.group[static_cast<std::size_t>(o)] < 0) {
          out.group[static_cast<std::size_t>(o)] = g;
          stack.push_back(static_cast<std::size_t>(o));
        }
    }
  }
  return out;
}

}  // namespace tessella
