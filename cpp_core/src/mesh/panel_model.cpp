#include "mesh/panel_model.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <unordered_map>

namespace tessella {

namespace {

constexpr double kPiDelaunay = 3.14159265358979323846;

double cross2(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

bool inside_triangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  return cross2(a, b, p) >= 0 && cross2(b, c, p) >= 0 && cross2(c, a, p) >= 0;
}

// Area of the bilinear patch by 4x4 Gauss-Legendre quadrature.
double bilinear_area(const std::vector<Vec3>& p) {
  static const double x[4] = {0.0694318442029737, 0.3300094782075719, 0.6699905217924281,
                              0.9305681557970263};
  static const double w[4] = {0.1739274225687269, 0.3260725774312731, 0.3260725774312731,
                              0.1739274225687269};
  double area = 0;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const double s = x[i], t = x[j];
      const Vec3 ds = (1 - t) * (p[1] - p[0]) + t * (p[2] - p[3]);
      const Vec3 dt = (1 - s) * (p[3] - p[0]) + s * (p[2] - p[1]);
      area += w[i] * w[j] * ds.cross(dt).norm();
    }
  }
  return area;
}

// Angle at b in triangle (a, b, c).
double angle_at(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 u = a - b, v = c - b;
  return std::atan2(std::abs(u.x() * v.y() - u.y() * v.x()), u.dot(v));
}

// The directed edges (a, b) of the triangles with their (tri, k), sorted by
// edge, triangles in order within an edge, and of repeated edges the last
// one kept.
void sorted_edges(const std::vector<std::array<int, 3>>& tris,
                  std::vector<std::pair<std::pair<int, int>, std::pair<int, int>>>& edge) {
  using Edge = std::pair<std::pair<int, int>, std::pair<int, int>>;
  edge.clear();
  edge.reserve(3 * tris.size());
  int corners = 0;
  for (const auto& t : tris) corners = std::max({corners, t[0] + 1, t[1] + 1, t[2] + 1});
  if (corners < (1 << 21) && 3 * tris.size() < (std::size_t(1) << 22)) {
    // Packed keys (a, b, 3 t + k) sort as the stable sort of (a, b) below does
    // (entries are made in (t, k) order), at a fraction of its cost.
    std::vector<std::uint64_t> keys;
    keys.reserve(3 * tris.size());
    for (std::size_t t = 0; t < tris.size(); ++t)
      for (int k = 0; k < 3; ++k)
        keys.push_back(std::uint64_t(tris[t][k]) << 43 | std::uint64_t(tris[t][(k + 1) % 3]) << 22 |
                       std::uint64_t(3 * t + k));
    std::sort(keys.begin(), keys.end());
    for (std::uint64_t key : keys) {
      const std::pair<int, int> e{int(key >> 43), int(key >> 22 & ((1u << 21) - 1))};
      const int tk = int(key & ((1u << 22) - 1));
      const Edge x{e, {tk / 3, tk % 3}};
      if (!edge.empty() && edge.back().first == e)
        edge.back() = x;
      else
        edge.push_back(x);
    }
    return;
  }
  std::vector<Edge> all;
  all.reserve(3 * tris.size());
  for (int t = 0; t < int(tris.size()); ++t)
    for (int k = 0; k < 3; ++k) all.push_back({{tris[t][k], tris[t][(k + 1) % 3]}, {t, k}});
  std::stable_sort(all.begin(), all.end(),
                   [](const Edge& x, const Edge& y) { return x.first < y.first; });
  for (const Edge& x : all) {
    if (!edge.empty() && edge.back().first == x.first)
      edge.back() = x;
    else
      edge.push_back(x);
  }
}

// Whether the angles at c in (a, c, b) and at d in (b, d, a) sum to more than
// pi (+1e-12): the sign of sin(alpha + beta) = sin a cos b + cos a sin b
// decides without atan2 where it is clear by a wide margin (1e-9 of the
// scale, far above rounding); near 0, pi or 2 pi the angles are summed as
// before, so every decision is the same.
bool opposite_angles_exceed_pi(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const Vec2 u1 = a - c, v1 = b - c, u2 = b - d, v2 = a - d;
  const double s1 = std::abs(u1.x() * v1.y() - u1.y() * v1.x()), c1 = u1.dot(v1);
  const double s2 = std::abs(u2.x() * v2.y() - u2.y() * v2.x()), c2 = u2.dot(v2);
  const double sine = s1 * c2 + c1 * s2;
  const double scale = u1.norm() * v1.norm() * u2.norm() * v2.norm();
  // alpha + beta lies in [0, 2 pi]: a clearly positive sine means below pi,
  // a clearly negative one above it.
  if (sine > 1e-9 * scale) return false;
  if (sine < -1e-9 * scale) return true;
  return angle_at(a, c, b) + angle_at(b, d, a) > kPiDelaunay + 1e-12;
}

// Flip decision and flip of the inner edge (a, b) of triangle t1 (at k1)
// whose twin (b, a) is in t2 (at k2); true if flipped.
bool flip_if_not_delaunay(const std::vector<Vec2>& uv, std::vector<std::array<int, 3>>& tris,
                          int t1, int k1, int t2, int k2) {
  const int a = tris[t1][k1], b = tris[t1][(k1 + 1) % 3];
  const int c = tris[t1][(k1 + 2) % 3];  // opposite in t1
  const int d = tris[t2][(k2 + 2) % 3];  // opposite in t2
  if (!opposite_angles_exceed_pi(uv[a], uv[b], uv[c], uv[d])) return false;
  // The quad a-d-b-c must be convex for the flip (c and d on both sides of a-b
  // is given; a and b must lie on both sides of c-d).
  const double sa = cross2(uv[c], uv[d], uv[a]), sb = cross2(uv[c], uv[d], uv[b]);
  if (!(sa * sb < 0)) return false;
  const bool ccw = cross2(uv[a], uv[b], uv[c]) > 0;
  tris[t1] = ccw ? std::array<int, 3>{c, a, d} : std::array<int, 3>{c, d, a};
  tris[t2] = ccw ? std::array<int, 3>{d, b, c} : std::array<int, 3>{d, c, b};
  return true;
}

// Lawson flips: an inner edge whose two opposite angles sum to more than pi is
// replaced by the other diagonal of its (convex) quad, until none is left.
// Ear clipping alone leaves long slivers between two runs of close outline
// points; mapped onto a curved surface such a sliver can even turn over.
// The outline edges never flip, so the result is the constrained Delaunay
// triangulation of the outline. Each pass visits every directed edge in
// sorted order and flips those whose triangles no flip of the pass touched
// yet (the definition; make_delaunay below gives the same flips faster).
void make_delaunay_by_passes(const std::vector<Vec2>& uv, std::vector<std::array<int, 3>>& tris) {
  for (int pass = 0; pass < 64; ++pass) {
    // Directed edge -> (tri, k), sorted by edge; of repeated edges the last
    // triangle counts. (A sorted vector: the order of a std::map, without its
    // allocations.)
    using Edge = std::pair<std::pair<int, int>, std::pair<int, int>>;
    std::vector<Edge> edge;
    sorted_edges(tris, edge);
    auto find = [&](const std::pair<int, int>& key) {
      auto it =
          std::lower_bound(edge.begin(), edge.end(), key,
                           [](const Edge& x, const std::pair<int, int>& k) { return x.first < k; });
      return it != edge.end() && it->first == key ? it : edge.end();
    };
    bool flipped = false;
    std::vector<char> touched(tris.size(), 0);
    for (const auto& [e, tk] : edge) {
      auto other = find({e.second, e.first});
      if (other == edge.end()) continue;  // an outline edge
      const int t1 = tk.first, t2 = other->second.first;
      if (touched[t1] || touched[t2]) continue;
      if (!flip_if_not_delaunay(uv, tris, t1, tk.second, t2, other->second.second)) continue;
      touched[t1] = touched[t2] = 1;
      flipped = true;
    }
    if (!flipped) break;
  }
}

// The passes of make_delaunay_by_passes, flip for flip, without visiting
// every edge in every pass: an edge whose two triangles no flip touched in
// the last pass was judged then, on the same four corners, and kept; so a
// pass only needs the edges of the triangles the last pass touched (and
// their twins), in the same sorted order. Directed edges live in a hash map
// (edge -> 3 t + k). A triangulation with a repeated directed edge (a
// degenerate ear), before or after a flip, goes to the passes themselves.
void make_delaunay(const std::vector<Vec2>& uv, std::vector<std::array<int, 3>>& tris) {
  int corners = 0;
  for (const auto& t : tris) corners = std::max({corners, t[0] + 1, t[1] + 1, t[2] + 1});
  if (corners >= (1 << 21) || 3 * tris.size() >= (std::size_t(1) << 30))
    return make_delaunay_by_passes(uv, tris);
  auto key = [](int a, int b) { return std::uint64_t(a) << 21 | std::uint64_t(b); };
  const std::vector<std::array<int, 3>> input = tris;
  std::unordered_map<std::uint64_t, int> edge;
  edge.reserve(6 * tris.size());
  for (int t = 0; t < int(tris.size()); ++t)
    for (int k = 0; k < 3; ++k)
      if (!edge.emplace(key(tris[t][k], tris[t][(k + 1) % 3]), 3 * t + k).second)
        return make_delaunay_by_passes(uv, tris);
  // This pass's directed edges (key, 3 t + k), sorted by key as the passes are.
  std::vector<std::pair<std::uint64_t, int>> todo;
  todo.reserve(edge.size());
  for (const auto& [e, tk] : edge) todo.emplace_back(e, tk);
  std::vector<char> touched(tris.size(), 0);
  std::vector<int> touched_list;
  for (int pass = 0; pass < 64 && !todo.empty(); ++pass) {
    std::sort(todo.begin(), todo.end());
    for (int t : touched_list) touched[t] = 0;
    touched_list.clear();
    for (const auto& [e, tk] : todo) {
      const int t1 = tk / 3, k1 = tk % 3;
      const int a = int(e >> 21), b = int(e & ((1u << 21) - 1));
      const auto other = edge.find(key(b, a));
      if (other == edge.end()) continue;  // an outline edge
      const int t2 = other->second / 3, k2 = other->second % 3;
      if (touched[t1] || touched[t2]) continue;
      const std::array<int, 3> old1 = tris[t1], old2 = tris[t2];
      if (!flip_if_not_delaunay(uv, tris, t1, k1, t2, k2)) continue;
      for (int k = 0; k < 3; ++k) {
        edge.erase(key(old1[k], old1[(k + 1) % 3]));
        edge.erase(key(old2[k], old2[(k + 1) % 3]));
      }
      for (int t : {t1, t2})
        for (int k = 0; k < 3; ++k)
          if (!edge.emplace(key(tris[t][k], tris[t][(k + 1) % 3]), 3 * t + k).second) {
            tris = input;  // a repeated edge after the flip: the passes decide
            return make_delaunay_by_passes(uv, tris);
          }
      touched[t1] = touched[t2] = 1;
      touched_list.push_back(t1);
      touched_list.push_back(t2);
    }
    // Next pass: the edges of the touched triangles and their twins.
    todo.clear();
    for (int t : touched_list)
      for (int k = 0; k < 3; ++k) {
        const int a = tris[t][k], b = tris[t][(k + 1) % 3];
        todo.emplace_back(key(a, b), 3 * t + k);
        const auto twin = edge.find(key(b, a));
        if (twin != edge.end()) todo.emplace_back(twin->first, twin->second);
      }
    std::sort(todo.begin(), todo.end());
    todo.erase(std::unique(todo.begin(), todo.end()), todo.end());
  }
}

}  // namespace

namespace {

std::vector<std::array<int, 3>> triangulate_outline(const std::vector<Vec2>& uv) {
  // A clockwise outline (a panel of a reversed face) is clipped as its
  // mirror image; the triangles then keep the outline's own turning sense.
  double area2 = 0;
  for (std::size_t i = 0; i < uv.size(); ++i) {
    const Vec2& p = uv[i];
    const Vec2& q = uv[(i + 1) % uv.size()];
    area2 += p.x() * q.y() - q.x() * p.y();
  }
  if (area2 < 0) {
    std::vector<Vec2> mirrored;
    for (const Vec2& q : uv) mirrored.emplace_back(q.x(), -q.y());
    std::vector<std::array<int, 3>> triangles = triangulate_outline(mirrored);
    return triangles;  // same indices: clockwise again in the original plane
  }
  // Ear clipping: the first corner (in outline order) that is convex and
  // whose triangle holds no other corner is cut. If rounding leaves no clean
  // ear, the most convex corner is cut so the result always has n-2
  // triangles. A corner's state only changes when a neighbour is cut (its
  // triangle changes) or when the corner inside its triangle is (the
  // blocker): the states are kept and only those recomputed, so each cut
  // costs O(n) instead of O(n^2), with the same cuts as a full rescan.
  std::vector<std::array<int, 3>> triangles;
  const int n0 = static_cast<int>(uv.size());
  std::vector<int> prev(n0), next(n0);
  for (int i = 0; i < n0; ++i) prev[i] = (i + n0 - 1) % n0, next[i] = (i + 1) % n0;
  enum State : char { kDirty, kEar, kReflex, kBlocked };
  std::vector<char> state(n0, kDirty);
  std::vector<int> blocker(n0, -1);
  std::vector<double> turn(n0, 0.0);
  int first = 0, size = n0;
  auto evaluate = [&](int k) {
    const Vec2& a = uv[prev[k]];
    const Vec2& b = uv[k];
    const Vec2& c = uv[next[k]];
    turn[k] = cross2(a, b, c);
    blocker[k] = -1;
    if (turn[k] <= 0) {
      state[k] = kReflex;
      return;
    }
    // The other corners in outline order, from the first one kept.
    int q = first;
    for (int m = 0; m < size; ++m, q = next[q]) {
      if (q == prev[k] || q == k || q == next[k]) continue;
      if (uv[q] == a || uv[q] == b || uv[q] == c) continue;
      if (inside_triangle(uv[q], a, b, c)) {
        state[k] = kBlocked;
        blocker[k] = q;
        return;
      }
    }
    state[k] = kEar;
  };
  while (size > 3) {
    int ear = -1, best = first;
    double best_turn = -INFINITY;
    int k = first;
    for (int m = 0; m < size; ++m, k = next[k]) {
      if (state[k] == kDirty) evaluate(k);
      if (turn[k] > best_turn) best_turn = turn[k], best = k;
      if (state[k] == kEar) {
        ear = k;
        break;
      }
    }
    if (ear < 0) ear = best;
    const int a = prev[ear], c = next[ear];
    triangles.push_back({a, ear, c});
    next[a] = c;
    prev[c] = a;
    if (ear == first) first = c;
    --size;
    state[a] = state[c] = kDirty;
    for (int q = first, m = 0; m < size; ++m, q = next[q])
      if (state[q] == kBlocked && blocker[q] == ear) state[q] = kDirty;
  }
  if (size == 3) triangles.push_back({first, next[first], next[next[first]]});
  make_delaunay(uv, triangles);
  return triangles;
}

// The triangulations of this thread's recent polygons: the metrics, the area
// and the exports triangulate the same boundary panel several times, and ear
// clipping with its Delaunay pass is quadratic in the corners. Keyed by the
// exact corner coordinates (compared in full on a hit), so a hit returns what
// the computation would; bounded in corners held, then cleared.
class TriangulationMemo {
 public:
  const std::vector<std::array<int, 3>>& get(const std::vector<Vec2>& uv) {
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the coordinate bits
    for (const Vec2& q : uv) {
      for (double x : {q.x(), q.y()}) {
        std::uint64_t bits;
        std::memcpy(&bits, &x, sizeof bits);
        h = (h ^ bits) * 1099511628211ull;
      }
    }
    auto range = entries_.equal_range(h);
    for (auto it = range.first; it != range.second; ++it)
      if (it->second.uv == uv) return it->second.triangles;
    if (corners_ + uv.size() > kMaxCorners) entries_.clear(), corners_ = 0;
    corners_ += uv.size();
    auto it = entries_.emplace(h, Entry{uv, triangulate_outline(uv)});
    return it->second.triangles;
  }

 private:
  static constexpr std::size_t kMaxCorners = 1 << 20;
  struct Entry {
    std::vector<Vec2> uv;
    std::vector<std::array<int, 3>> triangles;
  };
  std::unordered_multimap<std::uint64_t, Entry> entries_;
  std::size_t corners_ = 0;
};

}  // namespace

std::vector<std::array<int, 3>> triangulate_polygon(const std::vector<Vec2>& uv) {
  // Small polygons cost less to triangulate than to look up.
  if (uv.size() < 7) return triangulate_outline(uv);
  thread_local TriangulationMemo memo;
  return memo.get(uv);
}

double panel_model_area(const std::vector<Vec3>& xyz, const std::vector<Vec2>& uv) {
  if (xyz.size() == 4) return bilinear_area(xyz);
  double area = 0;
  for (const auto& t : triangulate_polygon(uv)) {
    area += 0.5 * (xyz[t[1]] - xyz[t[0]]).cross(xyz[t[2]] - xyz[t[0]]).norm();
  }
  return area;
}

namespace {
// Whether a quad's (u,v) corners turn the other way at some corner (a dent):
// its bilinear patch would fold over itself, counting the dent twice.
bool dented_quad(const std::vector<Vec2>& q) {
  double turn[4], largest = 0;
  for (int i = 0; i < 4; ++i) {
    const Vec2 a = q[(i + 1) % 4] - q[i], b = q[(i + 2) % 4] - q[(i + 1) % 4];
    turn[i] = a.x() * b.y() - a.y() * b.x();
    largest = std::max(largest, std::abs(turn[i]));
  }
  const double tol = 1e-12 * largest;
  bool left = false, right = false;
  for (double t : turn) left = left || t > tol, right = right || t < -tol;
  return left && right;
}
}  // namespace

bool modelled_as_pieces(const PanelMesh& mesh, std::size_t k) {
  const std::vector<int>& panel = mesh.panels[k];
  if (panel.size() > 4) return true;
  if (panel.size() < 4) return false;
  for (int v : panel)
    if (!is_node(mesh, v)) return true;
  // A dented quad of four nodes (e.g. half of a cell split around an opening,
  // split again) is no bilinear panel: it is bent along its inside diagonal.
  return dented_quad(panel_corner_uv(mesh, k));
}

const std::vector<std::array<int, 2>>& panel_bends(const PanelMesh& mesh, std::size_t k) {
  static const std::vector<std::array<int, 2>> none;
  return k < mesh.bends.size() ? mesh.bends[k] : none;
}

std::vector<std::vector<int>> split_polygon(int corners,
                                            const std::vector<std::array<int, 2>>& diagonals) {
  std::vector<std::vector<int>> pieces(1);
  for (int c = 0; c < corners; ++c) pieces[0].push_back(c);
  for (const auto& d : diagonals) {
    for (std::size_t p = 0; p < pieces.size(); ++p) {
      std::vector<int>& piece = pieces[p];
      const auto ia = std::find(piece.begin(), piece.end(), d[0]);
      const auto ib = std::find(piece.begin(), piece.end(), d[1]);
      if (ia == piece.end() || ib == piece.end()) continue;
      std::size_t i = static_cast<std::size_t>(ia - piece.begin());
      std::size_t j = static_cast<std::size_t>(ib - piece.begin());
      if (i > j) std::swap(i, j);
      if (j - i < 2 || (i == 0 && j + 1 == piece.size())) break;  // an outline edge
      std::vector<int> first(piece.begin() + static_cast<long>(i),
                             piece.begin() + static_cast<long>(j) + 1);
      std::vector<int> second(piece.begin() + static_cast<long>(j), piece.end());
      second.insert(second.end(), piece.begin(), piece.begin() + static_cast<long>(i) + 1);
      piece = std::move(first);
      pieces.push_back(std::move(second));
      break;
    }
  }
  return pieces;
}

std::vector<std::array<int, 3>> triangulate_pieces(const std::vector<Vec3>& xyz,
                                                   const std::vector<Vec2>& uv,
                                                   const std::vector<std::array<int, 2>>& bends) {
  std::vector<std::array<int, 3>> out;
  for (const std::vector<int>& piece : split_polygon(static_cast<int>(xyz.size()), bends)) {
    // A flat piece is triangulated on its own plane (Newell's normal, which
    // follows the corner order), where it is cut: in (u,v) a thin triangle could
    // turn over once the trim points sit on the plane. A piece left curved (on
    // the surface: the boundary stage kept it) is triangulated in (u,v).
    Vec3 normal = Vec3::Zero(), centre = Vec3::Zero();
    for (std::size_t i = 0; i < piece.size(); ++i) {
      normal += xyz[piece[i]].cross(xyz[piece[(i + 1) % piece.size()]]);
      centre += xyz[piece[i]];
    }
    centre /= double(piece.size());
    double extent = 0, off = 0;
    if (normal.norm() > 0) {
      normal.normalize();
      for (int c : piece) {
        extent = std::max(extent, (xyz[c] - centre).norm());
        off = std::max(off, std::abs((xyz[c] - centre).dot(normal)));
      }
    }
    const bool flat = normal.norm() > 0 && off <= 1e-9 * extent;
    std::vector<Vec2> sub;
    if (flat) {
      const Vec3 e1 = normal.unitOrthogonal(), e2 = normal.cross(e1);
      for (int c : piece) sub.emplace_back(xyz[c].dot(e1), xyz[c].dot(e2));
    } else {
      for (int c : piece) sub.push_back(uv[c]);
    }
    for (const auto& t : triangulate_polygon(sub))
      out.push_back({piece[t[0]], piece[t[1]], piece[t[2]]});
  }
  return out;
}

std::vector<std::array<int, 3>> panel_model_triangles(const PanelMesh& mesh, std::size_t k) {
  const std::size_t n = mesh.panels[k].size();
  if (n == 3) return {{0, 1, 2}};
  if (!modelled_as_pieces(mesh, k)) return {};
  std::vector<Vec3> xyz;
  for (int v : mesh.panels[k]) xyz.push_back(mesh.xyz[v]);
  return triangulate_pieces(xyz, panel_corner_uv(mesh, k), panel_bends(mesh, k));
}

double panel_area(const PanelMesh& mesh, std::size_t p) {
  std::vector<Vec3> xyz;
  for (int v : mesh.panels[p]) xyz.push_back(mesh.xyz[v]);
  const auto tris = panel_model_triangles(mesh, p);
  if (tris.empty()) return bilinear_area(xyz);
  double area = 0;
  for (const auto& t : tris)
    area += 0.5 * (xyz[t[1]] - xyz[t[0]]).cross(xyz[t[2]] - xyz[t[0]]).norm();
  return area;
}

}  // namespace tessella
