#include "methods/boundary_driven/bd_onto_trim.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "geometry/segment_closest.h"
#include "methods/boundary_driven/bd_trim_crossing.h"

namespace tessella {

namespace {

using EdgeUses = std::map<std::pair<int, int>, int>;

EdgeUses edge_uses(const BdNetwork& net) {
  EdgeUses uses;
  for (const auto& p : net.panels)
    for (std::size_t i = 0; i < p.size(); ++i) {
      const int a = p[i], b = p[(i + 1) % p.size()];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  return uses;
}

// An edge along a trim: one panel, both ends on the same loop.
bool trim_edge(const BdNetwork& net, const EdgeUses& uses, int a, int b) {
  const BdNode &na = net.nodes[static_cast<std::size_t>(a)],
               &nb = net.nodes[static_cast<std::size_t>(b)];
  return na.loop >= 0 && na.loop == nb.loop && uses.at({std::min(a, b), std::max(a, b)}) == 1;
}

// The interior nodes with a rod across a trim, in index order: one pass over
// the panels' sides.
std::vector<int> nodes_with_rods_across(const BdNetwork& net, const EdgeUses& uses,
                                        const bd::TrimCrossingTest& trim) {
  std::vector<char> across(net.nodes.size(), 0);
  for (const auto& p : net.panels)
    for (std::size_t i = 0; i < p.size(); ++i) {
      const int a = p[i], b = p[(i + 1) % p.size()];
      if (a < b && !trim_edge(net, uses, a, b) &&
          trim.crosses(net.nodes[static_cast<std::size_t>(a)],
                       net.nodes[static_cast<std::size_t>(b)]))
        across[static_cast<std::size_t>(a)] = across[static_cast<std::size_t>(b)] = 1;
    }
  std::vector<int> out;
  for (std::size_t v = 0; v < across.size(); ++v)
    if (across[v] && net.nodes[v].loop < 0) out.push_back(static_cast<int>(v));
  return out;
}

struct TrimPoint {
  int loop = -1;
  double s = 0.0, distance = 1e300;
};

// The nearest point, in 3D, of the trim polylines to p.
TrimPoint nearest_trim_point(const std::vector<BdPolyline>& boundary, const Vec3& p) {
  TrimPoint best;
  for (std::size_t li = 0; li < boundary.size(); ++li) {
    const BdPolyline& l = boundary[li];
    for (int i = 0; i < l.segment_count(); ++i) {
      const Vec3& a = l.xyz[static_cast<std::size_t>(i)];
      const Vec3& b = l.xyz[(static_cast<std::size_t>(i) + 1) % l.xyz.size()];
      const double t = closest_fraction(a, Vec3(b - a), p);
      const double d = (a + t * (b - a) - p).norm();
      if (d < best.distance) best = {static_cast<int>(li), l.s_at(i, t), d};
    }
  }
  return best;
}

// Forward distance along a closed loop of length len from s0 to s1.
double ahead(double s0, double s1, double len) {
  double d = std::fmod(s1 - s0, len);
  return d < 0 ? d + len : d;
}

// Splits panel p, whose trim side p[i] -> p[i + 1] now runs through its node
// v, at v: the part from v round to p[i] and the part from p[i + 1] round to
// v, each closed along the trim. Parts of fewer than three nodes are slivers
// of no width and go.
void split_at(std::vector<std::vector<int>>& panels, std::size_t pi, std::size_t i, int v) {
  const std::vector<int> p = panels[pi];
  const std::size_t n = p.size();
  const std::size_t j = static_cast<std::size_t>(std::find(p.begin(), p.end(), v) - p.begin());
  std::vector<int> first, second;
  for (std::size_t k = j;; k = (k + 1) % n) {  // v ... p[i]
    first.push_back(p[k]);
    if (k == i) break;
  }
  for (std::size_t k = (i + 1) % n;; k = (k + 1) % n) {  // p[i + 1] ... v
    second.push_back(p[k]);
    if (k == j) break;
  }
  panels.erase(panels.begin() + static_cast<std::ptrdiff_t>(pi));
  for (auto* part : {&second, &first})
    if (part->size() >= 3) panels.insert(panels.begin() + static_cast<std::ptrdiff_t>(pi), *part);
}

}  // namespace

int move_crossing_nodes_onto_trims(const SurfaceFace& face, const std::vector<BdPolyline>& boundary,
                                   BdNetwork& net, double reach) {
  const bd::TrimCrossingTest trim(boundary);
  int moved = 0;
  // One node at a time (each move changes the panels around it); a node
  // moves at most once, so this ends.
  for (bool changed = true; changed;) {
    changed = false;
    const EdgeUses uses = edge_uses(net);
    for (const int v : nodes_with_rods_across(net, uses, trim)) {
      if (changed) break;
      BdNode& node = net.nodes[static_cast<std::size_t>(v)];
      if (node.corner || node.shared) continue;
      const TrimPoint q = nearest_trim_point(boundary, node.xyz);
      if (!(q.distance <= reach)) continue;
      const BdPolyline& line = boundary[static_cast<std::size_t>(q.loop)];
      const double len = line.length();
      for (std::size_t pi = 0; pi < net.panels.size() && !changed; ++pi) {
        const auto& p = net.panels[pi];
        if (std::find(p.begin(), p.end(), v) == p.end()) continue;
        for (std::size_t i = 0; i < p.size(); ++i) {
          const int a = p[i], b = p[(i + 1) % p.size()];
          if (net.nodes[static_cast<std::size_t>(a)].loop != q.loop || !trim_edge(net, uses, a, b))
            continue;
          const double sa = net.nodes[static_cast<std::size_t>(a)].s;
          const double run = ahead(sa, net.nodes[static_cast<std::size_t>(b)].s, len);
          const double at = ahead(sa, q.s, len);
          if (!(at > 0 && at < run)) continue;
          node.loop = q.loop, node.s = q.s;
          node.uv = face.snap_to_trim(q.loop, line.uv_at(q.s));
          node.xyz = face.point(node.uv.x(), node.uv.y());
          split_at(net.panels, pi, i, v);
          changed = true;
          ++moved;
          break;
        }
      }
    }
  }
  return moved;
}

}  // namespace tessella
