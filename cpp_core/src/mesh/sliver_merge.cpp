// Merging boundary slivers into a neighbour: a tiny panel cut off by a trim
// curve is worse for a workshop than a slightly larger neighbour.
#include "mesh/sliver_merge.h"

#include <algorithm>
#include <map>
#include <numeric>

#include "mesh/panel_model.h"
#include "tessella/errors.h"

namespace tessella {

namespace {

// Union of two panels sharing exactly one contiguous chain of edges (a walks
// the chain one way, b the other). Returns false if they share none or more.
bool merge_pair(const std::vector<int>& a, const std::vector<int>& b, std::vector<int>& out) {
  const std::size_t na = a.size(), nb = b.size();
  std::map<std::pair<int, int>, std::size_t> b_edge;  // directed edge of b -> index
  for (std::size_t k = 0; k < nb; ++k) b_edge[{b[k], b[(k + 1) % nb]}] = k;
  std::vector<char> shared(na, 0);  // edge k of a (a[k] -> a[k+1]) is shared
  std::size_t count = 0;
  for (std::size_t k = 0; k < na; ++k) {
    if (b_edge.count({a[(k + 1) % na], a[k]})) shared[k] = 1, ++count;
  }
  if (count == 0 || count == na || count == nb) return false;
  // One contiguous run: exactly one place where "not shared" is followed by "shared".
  std::size_t starts = 0, first = 0;
  for (std::size_t k = 0; k < na; ++k) {
    if (shared[k] && !shared[(k + na - 1) % na]) ++starts, first = k;
  }
  if (starts != 1) return false;
  const std::size_t last = (first + count) % na;  // a[last] ends the chain
  // a from the chain's end around to its start, then b from the chain's start
  // (where b leaves it) around to just before the chain's end.
  out.clear();
  for (std::size_t k = last; k != first; k = (k + 1) % na) out.push_back(a[k]);
  out.push_back(a[first]);
  const std::size_t kb = b_edge.at({a[(first + 1) % na], a[first]});  // b edge into a[first]
  for (std::size_t k = (kb + 2) % nb; b[k] != a[last]; k = (k + 1) % nb) out.push_back(b[k]);
  // A polygon must not visit a vertex twice (the panels touched elsewhere).
  std::vector<int> sorted = out;
  std::sort(sorted.begin(), sorted.end());
  return std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end() && out.size() >= 3;
}

// Panel s joined into its neighbour n as `joined` (merge_pair's union):
// corner_uv follows, each corner keeping the (u,v) it had in the panel it
// came from (the neighbour's where both have it: the seam side the
// neighbour is on), and the directed-edge owners are brought up to date.
void join_into(PanelMesh& mesh, int n, int s, std::vector<int> joined,
               std::map<std::pair<int, int>, int>& owner) {
  if (!mesh.corner_uv.empty()) {
    std::map<int, Vec2> seen;
    for (std::size_t k = 0; k < mesh.panels[s].size(); ++k)
      seen[mesh.panels[s][k]] = mesh.corner_uv[s][k];
    for (std::size_t k = 0; k < mesh.panels[n].size(); ++k)
      seen[mesh.panels[n][k]] = mesh.corner_uv[n][k];
    std::vector<Vec2> corner;
    for (int v : joined) corner.push_back(seen.at(v));
    mesh.corner_uv[n] = std::move(corner);
  }
  for (std::size_t k = 0; k < joined.size(); ++k)
    owner[{joined[k], joined[(k + 1) % joined.size()]}] = n;
  mesh.panels[n] = std::move(joined);
}

std::map<std::pair<int, int>, int> edge_owners(const PanelMesh& mesh) {
  std::map<std::pair<int, int>, int> owner;
  for (std::size_t p = 0; p < mesh.panels.size(); ++p) {
    const auto& poly = mesh.panels[p];
    for (std::size_t k = 0; k < poly.size(); ++k)
      owner[{poly[k], poly[(k + 1) % poly.size()]}] = int(p);
  }
  return owner;
}

// Keeps the panels (and their corner_uv, folds stay) whose flag is set.
void drop_panels(PanelMesh& mesh, const std::vector<char>& keep) {
  std::vector<std::vector<int>> kept;
  std::vector<std::vector<Vec2>> kept_uv;
  for (std::size_t p = 0; p < mesh.panels.size(); ++p) {
    if (!keep[p]) continue;
    kept.push_back(std::move(mesh.panels[p]));
    if (!mesh.corner_uv.empty()) kept_uv.push_back(std::move(mesh.corner_uv[p]));
  }
  mesh.panels = std::move(kept);
  if (!mesh.corner_uv.empty()) mesh.corner_uv = std::move(kept_uv);
}

// A lower bound of panel_area: the length of the vector area of the corner
// polygon, (1/2) |sum p_k x p_k+1|. Any surface with that outline (the
// bilinear patch, the flat pieces) has at least this area (|integral of n dA|
// <= integral of dA); the factor covers rounding. Exact areas triangulate a
// boundary panel's many-cornered outline (four times a panel in the grids'
// pipeline), needed only where the bound cannot decide.
double area_lower_bound(const PanelMesh& mesh, std::size_t p) {
  const std::vector<int>& poly = mesh.panels[p];
  if (poly.size() < 3) return 0.0;
  Vec3 sum = Vec3::Zero();
  const Vec3& origin = mesh.xyz[poly[0]];
  for (std::size_t k = 1; k + 1 < poly.size(); ++k)
    sum += (mesh.xyz[poly[k]] - origin).cross(mesh.xyz[poly[k + 1]] - origin);
  return 0.5 * sum.norm() * (1 - 1e-9);
}

// panel_area(mesh, p) where it may be below `threshold`; where the lower
// bound shows it is not, that bound (at least the threshold).
double area_unless_above(const PanelMesh& mesh, std::size_t p, double threshold) {
  const double lower = area_lower_bound(mesh, p);
  return lower >= threshold ? lower : panel_area(mesh, p);
}

}  // namespace

int merge_slivers(PanelMesh& mesh, double fraction, const std::vector<double>& reference_area) {
  require_in_range("sliver_fraction", fraction, 0.0, 1.0);
  if (fraction <= 0) return 0;
  // Exact areas of the slivers; a panel shown to be none keeps a lower bound
  // (it is never merged away, and a sliver merged into it leaves it none).
  std::vector<double> area(mesh.panels.size());
  for (std::size_t p = 0; p < mesh.panels.size(); ++p)
    area[p] = area_unless_above(mesh, p, fraction * reference_area[p]);
  // No sliver at all (the usual case): nothing to merge, skip the edge map.
  bool any = false;
  for (std::size_t p = 0; p < mesh.panels.size() && !any; ++p)
    any = area[p] < fraction * reference_area[p];
  if (!any) return 0;
  std::vector<char> alive(mesh.panels.size(), 1);
  // Directed edge -> panel, kept up to date as panels merge.
  std::map<std::pair<int, int>, int> owner = edge_owners(mesh);
  std::vector<int> order(mesh.panels.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return area[a] < area[b]; });
  int merged = 0;
  for (int s : order) {
    if (!alive[s] || area[s] >= fraction * reference_area[s]) continue;
    // Neighbour with the longest shared boundary (3D length).
    std::map<int, double> shared_length;
    const auto& poly = mesh.panels[s];
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const int a = poly[k], b = poly[(k + 1) % poly.size()];
      auto it = owner.find({b, a});
      if (it != owner.end() && alive[it->second] && it->second != s) {
        shared_length[it->second] += (mesh.xyz[a] - mesh.xyz[b]).norm();
      }
    }
    std::vector<std::pair<double, int>> candidates;
    for (auto& [p, len] : shared_length) candidates.push_back({-len, p});
    std::sort(candidates.begin(), candidates.end());
    for (auto& [neg_len, n] : candidates) {
      std::vector<int> joined;
      if (!merge_pair(mesh.panels[n], poly, joined)) continue;
      join_into(mesh, n, s, std::move(joined), owner);
      area[n] += area[s];
      alive[s] = 0;
      ++merged;
      break;
    }
  }
  drop_panels(mesh, alive);
  return merged;
}

namespace {

// Corner angle (deg, 3D) at vertex `at` between its outline neighbours; 180
// where a side has no length.
double corner_deg(const PanelMesh& mesh, int prev, int at, int next) {
  const Vec3 a = mesh.xyz[prev] - mesh.xyz[at], b = mesh.xyz[next] - mesh.xyz[at];
  const double la = a.norm(), lb = b.norm();
  if (la == 0 || lb == 0) return 180.0;
  return std::acos(std::clamp(a.dot(b) / (la * lb), -1.0, 1.0)) * 180.0 / 3.14159265358979323846;
}

// Smallest corner angle (deg, 3D) of a panel's whole outline.
double sharpest_corner(const PanelMesh& mesh, const std::vector<int>& poly) {
  const std::size_t n = poly.size();
  double worst = 180.0;
  for (std::size_t k = 0; k < n; ++k)
    worst = std::min(worst, corner_deg(mesh, poly[(k + n - 1) % n], poly[k], poly[(k + 1) % n]));
  return worst;
}

int node_count(const PanelMesh& mesh, const std::vector<int>& poly) {
  return static_cast<int>(
      std::count_if(poly.begin(), poly.end(), [&](int v) { return is_node(mesh, v); }));
}

}  // namespace

int merge_spikes(PanelMesh& mesh, double min_corner_deg, int max_nodes) {
  require_in_range("spike corner (deg)", min_corner_deg, 0.0, 90.0);
  if (min_corner_deg <= 0) return 0;
  std::vector<double> sharpest(mesh.panels.size());
  bool any = false;
  for (std::size_t p = 0; p < mesh.panels.size(); ++p) {
    sharpest[p] = sharpest_corner(mesh, mesh.panels[p]);
    any = any || sharpest[p] < min_corner_deg;
  }
  if (!any) return 0;
  std::vector<char> alive(mesh.panels.size(), 1);
  std::map<std::pair<int, int>, int> owner = edge_owners(mesh);
  int merged = 0;
  for (std::size_t s = 0; s < mesh.panels.size(); ++s) {
    if (!alive[s] || !(sharpest[s] < min_corner_deg)) continue;
    const std::vector<int> poly = mesh.panels[s];
    const std::size_t n = poly.size();
    // The neighbours across a rod (node to node) at a spike, best union first.
    int best = -1;
    double best_sharpest = sharpest[s];
    std::vector<int> best_joined;
    for (std::size_t k = 0; k < n; ++k) {
      const int a = poly[k], b = poly[(k + 1) % n];
      if (!is_node(mesh, a) || !is_node(mesh, b)) continue;
      // the side must end at a spike
      const double at_a = corner_deg(mesh, poly[(k + n - 1) % n], a, b);
      const double at_b = corner_deg(mesh, a, b, poly[(k + 2) % n]);
      if (!(std::min(at_a, at_b) < min_corner_deg)) continue;
      auto it = owner.find({b, a});
      if (it == owner.end() || !alive[it->second] || it->second == int(s)) continue;
      std::vector<int> joined;
      if (!merge_pair(mesh.panels[it->second], poly, joined)) continue;
      if (node_count(mesh, joined) > max_nodes) continue;
      const double q = sharpest_corner(mesh, joined);
      if (q > best_sharpest) best = it->second, best_sharpest = q, best_joined = std::move(joined);
    }
    if (best < 0) continue;
    join_into(mesh, best, int(s), std::move(best_joined), owner);
    sharpest[best] = best_sharpest;
    alive[s] = 0;
    ++merged;
  }
  if (merged > 0) {
    drop_panels(mesh, alive);
    build_rods(mesh);
  }
  return merged;
}

int remove_zero_area_panels(PanelMesh& mesh, double model_size) {
  const double min_area = mesh.nominal_area > 0
                              ? kZeroAreaFraction * mesh.nominal_area
                              : 1e-3 * kZeroAreaFraction * model_size * model_size;
  std::vector<double> reference(mesh.panels.size(), min_area);
  const std::size_t before = mesh.panels.size();
  merge_slivers(mesh, 1.0, reference);
  // What could not be merged (no neighbour along a contiguous edge chain)
  // covers nothing: drop it.
  std::vector<char> keep(mesh.panels.size(), 1);
  for (std::size_t p = 0; p < mesh.panels.size(); ++p)
    keep[p] = area_unless_above(mesh, p, min_area) >= min_area;
  drop_panels(mesh, keep);
  const int removed = static_cast<int>(before - mesh.panels.size());
  if (removed > 0) {
    remove_unused_vertices(mesh);
    // A fold whose two triangles both went has lost its vertices.
    mesh.folds.erase(std::remove_if(mesh.folds.begin(), mesh.folds.end(),
                                    [](const std::array<int, 2>& f) { return f[0] < 0; }),
                     mesh.folds.end());
    build_rods(mesh);
  }
  return removed;
}

}  // namespace tessella
