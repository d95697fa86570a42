#include "mesh/boundary_pieces.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

#include "geometry/parallel_in_scopes.h"
#include "mesh/panel_model.h"
#include "tessella/errors.h"
#include "tessella/surface_face.h"

namespace tessella {

namespace {

using Diagonal = std::array<int, 2>;

constexpr int kMaxRefinements = 12;

struct Plane {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  // unit
};

// A panel being modelled: its vertices and their (u,v) as this panel sees them.
struct Draft {
  std::vector<int> vertices;
  std::vector<Vec2> uv;
};

double cross2(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

bool segments_touch(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double o1 = cross2(a, b, c), o2 = cross2(a, b, d);
  const double o3 = cross2(c, d, a), o4 = cross2(c, d, b);
  return ((o1 >= 0) != (o2 >= 0) || o1 == 0 || o2 == 0) &&
         ((o3 >= 0) != (o4 >= 0) || o3 == 0 || o4 == 0) &&
         std::max(a.x(), b.x()) >= std::min(c.x(), d.x()) &&
         std::max(c.x(), d.x()) >= std::min(a.x(), b.x()) &&
         std::max(a.y(), b.y()) >= std::min(c.y(), d.y()) &&
         std::max(c.y(), d.y()) >= std::min(a.y(), b.y());
}

bool inside_polygon(const Vec2& q, const std::vector<Vec2>& poly) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2 &a = poly[i], &b = poly[j];
    if ((a.y() > q.y()) != (b.y() > q.y()) &&
        q.x() < a.x() + (q.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
      in = !in;
  }
  return in;
}

// Whether the straight (u,v) segment between corners i and j runs inside the
// outline (crosses no edge not ending at i or j, midpoint inside): a bend line
// or a new rod must lie on the panel.
bool diagonal_inside(const std::vector<Vec2>& uv, int i, int j) {
  const int n = static_cast<int>(uv.size());
  for (int a = 0; a < n; ++a) {
    const int b = (a + 1) % n;
    if (a == i || a == j || b == i || b == j) continue;
    if (segments_touch(uv[i], uv[j], uv[a], uv[b])) return false;
  }
  return inside_polygon(0.5 * (uv[i] + uv[j]), uv);
}

// Whether two non-adjacent edges of the closed polygon cross properly (each
// strictly on both sides of the other: repeated or collinear outline points do
// not count): a piece whose outline, put on its plane, crosses itself cannot
// be cut.
bool crosses_itself(const std::vector<Vec2>& p) {
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 &a = p[i], &b = p[(i + 1) % n];
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;
      const Vec2 &c = p[j], &d = p[(j + 1) % n];
      if (cross2(a, b, c) * cross2(a, b, d) < 0 && cross2(c, d, a) * cross2(c, d, b) < 0)
        return true;
    }
  }
  return false;
}

Vec3 triangle_normal(const Vec3& a, const Vec3& b, const Vec3& c) { return (b - a).cross(c - a); }

double angle_between(const Vec3& n1, const Vec3& n2) {
  const double l = n1.norm() * n2.norm();
  if (!(l > 0)) return 180.0;
  return std::atan2(n1.cross(n2).norm(), n1.dot(n2)) * 180.0 / 3.14159265358979323846;
}

// Least-squares plane through `fixed` (0, 1 or 2 points that must lie on it)
// fitted to `points`: a piece with fewer than three (non-collinear) nodes.
Plane fit_plane(const std::vector<Vec3>& points, const std::vector<Vec3>& fixed) {
  Plane plane;
  Vec3 origin = Vec3::Zero();
  if (!fixed.empty()) {
    origin = fixed[0];
  } else {
    for (const Vec3& p : points) origin += p;
    origin /= double(std::max<std::size_t>(1, points.size()));
  }
  plane.point = origin;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3& p : points) cov += (p - origin) * (p - origin).transpose();
  if (fixed.size() >= 2 && (fixed[1] - fixed[0]).norm() > 0) {
    // The plane holds the line through the two fixed points: its normal is
    // the best one perpendicular to that line.
    const Vec3 d = (fixed[1] - fixed[0]).normalized();
    const Vec3 e1 = d.unitOrthogonal(), e2 = d.cross(e1);
    Eigen::Matrix2d c2;
    c2 << e1.dot(cov * e1), e1.dot(cov * e2), e2.dot(cov * e1), e2.dot(cov * e2);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(c2);
    const Eigen::Vector2d v = eig.eigenvectors().col(0);
    plane.normal = (v.x() * e1 + v.y() * e2).normalized();
    return plane;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  plane.normal = eig.eigenvectors().col(0).normalized();
  return plane;
}

class PieceModeller {
 public:
  // `original`: the vertex positions on the surface before the stage (the
  // modellers of one stage share them). A modeller's panels, counts and
  // report go to its own lists; it writes the mesh only where its panels'
  // own trim points move or become nodes (see model_boundary_pieces).
  PieceModeller(const SurfaceFace& face, PanelMesh& mesh, const BoundaryPiecesParams& params,
                BoundaryPiecesReport& report, const std::vector<Vec3>& original)
      : face_(face), mesh_(mesh), params_(params), report_(report), original_(original) {}

  // Models one draft; appends the resulting panel(s) to the output lists.
  void model(Draft draft, int origin) {
    for (int round = 0;; ++round) {
      std::vector<int> nodes;
      for (int c = 0; c < int(draft.vertices.size()); ++c)
        if (is_node(mesh_, draft.vertices[c])) nodes.push_back(c);
      const int k = static_cast<int>(nodes.size());
      if (k > params_.max_bends + 3) {
        if (split(draft, nodes, origin)) return;
        if (round < kMaxRefinements && params_.may_add_nodes && promote_middle(draft)) continue;
        keep(draft, origin);
        return;
      }
      std::vector<Diagonal> bends;
      if (k >= 4 && !choose_bends(draft, nodes, bends)) {
        // Every bend line would leave the panel (a trim curving into it):
        // a node in the middle of the longest trim run sees both its ends.
        if (round < kMaxRefinements && params_.may_add_nodes && promote_middle(draft)) continue;
        keep(draft, origin);
        return;
      }
      // Pieces and their planes; the trim points' offsets from them.
      std::vector<Vec3> xyz;
      for (int v : draft.vertices) xyz.push_back(original_[v]);
      std::vector<Vec3> placed = xyz;
      int worst = -1;
      double worst_offset = 0;
      bool tangled = false;
      for (const std::vector<int>& piece : split_polygon(int(xyz.size()), bends)) {
        const Plane plane = piece_plane(draft, xyz, piece);
        const Vec3 e1 = plane.normal.unitOrthogonal(), e2 = plane.normal.cross(e1);
        std::vector<Vec2> on_plane;
        for (int c : piece) {
          if (!is_node(mesh_, draft.vertices[c])) {
            const double off = (xyz[c] - plane.point).dot(plane.normal);
            placed[c] = xyz[c] - off * plane.normal;
            if (std::abs(off) > worst_offset) worst_offset = std::abs(off), worst = c;
          }
          on_plane.emplace_back((placed[c] - plane.point).dot(e1),
                                (placed[c] - plane.point).dot(e2));
        }
        // A trim curving away from the plane can fold its projection over.
        if (piece.size() > 3 && crosses_itself(on_plane)) tangled = true;
      }
      // Refined while its outline on the plane crosses itself or it deviates
      // more than allowed (trim offset first: it needs no sampling): the trim
      // point farthest from its plane becomes a node (it stays on the trim),
      // and the panel is modelled again.
      const bool too_far = params_.max_deviation > 0 &&
                           (worst_offset > params_.max_deviation ||
                            node_triangles_deviation(draft, xyz, bends) > params_.max_deviation);
      // At most kMaxRefinements new nodes per panel: beyond that the piece is
      // kept and its deviation reported as measured.
      if (tangled && (worst < 0 || round >= kMaxRefinements)) {
        // Still crossing itself on its plane: not cuttable as a flat piece;
        // kept on the surface as before this stage (a curved piece).
        keep(std::move(draft), origin);
        return;
      }
      if (worst >= 0 && (tangled || too_far) && round < kMaxRefinements && !params_.may_add_nodes) {
        // No new node allowed: a tangled piece stays curved on the surface,
        // one too far is kept as it is (its deviation is reported).
        if (tangled)
          keep(std::move(draft), origin);
        else
          finish(std::move(draft), std::move(bends), placed, origin);
        return;
      }
      if (worst >= 0 && (tangled || too_far) && round < kMaxRefinements) {
        // The new node keeps min_node_spacing from its neighbours on the trim
        // (no short rods); a piece that only a closer node would improve is
        // kept as it is (its deviation is reported as measured), unless its
        // outline crosses itself or the allowance is a hard bound.
        const int spaced = farthest_spaced_point(draft, placed, xyz);
        if (spaced < 0 && !tangled && !params_.hard_bound) {
          finish(std::move(draft), std::move(bends), placed, origin);
          return;
        }
        mesh_.is_node[draft.vertices[spaced >= 0 ? spaced : worst]] = 1;
        ++report_.refined;
        continue;
      }
      finish(std::move(draft), std::move(bends), placed, origin);
      return;
    }
  }

  // Kept as it is: not a piece panel, or one the stage cannot model (no bend
  // line or split inside it, or an outline that stays crossed on its plane):
  // left on the surface, triangulated in (u,v), as before this stage.
  void keep(Draft draft, int origin) { emit(std::move(draft), {}, origin, false); }

  std::vector<std::vector<int>> panels;
  std::vector<std::vector<Vec2>> corner_uv;
  std::vector<std::vector<Diagonal>> bends;

 private:
  void emit(Draft draft, std::vector<Diagonal> panel_bends, int origin, bool changed) {
    panels.push_back(std::move(draft.vertices));
    corner_uv.push_back(std::move(draft.uv));
    bends.push_back(std::move(panel_bends));
    report_.origin.push_back(origin);
    report_.changed.push_back(changed ? 1 : 0);
  }

  // Deviation of the pieces' interiors: samples of each piece's node triangle
  // projected onto the surface (with the trim points' offsets this bounds the
  // piece; the metrics later sample the whole piece). No triangulation of the
  // outline, so a refinement round stays cheap.
  double node_triangles_deviation(const Draft& draft, const std::vector<Vec3>& xyz,
                                  const std::vector<Diagonal>& bends) const {
    double worst = 0;
    const int n = params_.samples;
    for (const std::vector<int>& piece : split_polygon(int(xyz.size()), bends)) {
      std::vector<int> nodes;
      for (int c : piece)
        if (is_node(mesh_, draft.vertices[c])) nodes.push_back(c);
      if (nodes.size() != 3) continue;
      const Vec3 &a = xyz[nodes[0]], &b = xyz[nodes[1]], &c = xyz[nodes[2]];
      const Vec2 &ua = draft.uv[nodes[0]], &ub = draft.uv[nodes[1]], &uc = draft.uv[nodes[2]];
      for (int i = 0; i <= n; ++i)
        for (int j = 0; i + j <= n; ++j) {
          const double s = double(i) / n, t = double(j) / n, r = 1 - s - t;
          worst = std::max(worst,
                           face_.project(r * a + s * b + t * c, r * ua + s * ub + t * uc).distance);
        }
    }
    return worst;
  }

  void finish(Draft draft, std::vector<Diagonal> bends, const std::vector<Vec3>& placed,
              int origin) {
    // Nodes stay where they are (placed there already): only the panel's own
    // trim points are written (a node is shared with other panels, whose
    // modellers may run on other threads).
    for (std::size_t c = 0; c < draft.vertices.size(); ++c)
      if (!is_node(mesh_, draft.vertices[c])) mesh_.xyz[draft.vertices[c]] = placed[c];
    report_.bends += static_cast<int>(bends.size());
    ++report_.modelled;
    emit(std::move(draft), std::move(bends), origin, true);
  }

  // The trim point farthest from its piece plane (placed vs on the surface)
  // whose straight distance to the nearest node before and after it along the
  // outline (the rods it would end) is at least min_node_spacing; -1 if none.
  int farthest_spaced_point(const Draft& draft, const std::vector<Vec3>& placed,
                            const std::vector<Vec3>& xyz) const {
    const int n = static_cast<int>(draft.vertices.size());
    auto neighbour_node = [&](int c, int step) {
      for (int s = 1; s < n; ++s) {
        const int d = ((c + step * s) % n + n) % n;
        if (is_node(mesh_, draft.vertices[d])) return d;
      }
      return c;
    };
    int best = -1;
    double best_offset = 0;
    for (int c = 0; c < n; ++c) {
      if (is_node(mesh_, draft.vertices[c])) continue;
      const double before = (xyz[c] - xyz[neighbour_node(c, -1)]).norm();
      const double after = (xyz[c] - xyz[neighbour_node(c, 1)]).norm();
      if (std::min(before, after) < params_.min_node_spacing) continue;
      const double off = (placed[c] - xyz[c]).norm();
      if (off > best_offset) best_offset = off, best = c;
    }
    return best;
  }

  // Makes the middle point of the longest run of trim points a node; false if
  // the panel has no trim point left.
  bool promote_middle(const Draft& draft) {
    const int n = static_cast<int>(draft.vertices.size());
    int first_node = -1;
    for (int c = 0; c < n && first_node < 0; ++c)
      if (is_node(mesh_, draft.vertices[c])) first_node = c;
    if (first_node < 0) return false;
    int best_start = -1, best_len = 0;
    for (int s = 0; s < n;) {
      const int c = (first_node + s) % n;
      if (is_node(mesh_, draft.vertices[c])) {
        ++s;
        continue;
      }
      int len = 0;
      while (s + len < n && !is_node(mesh_, draft.vertices[(first_node + s + len) % n])) ++len;
      if (len > best_len) best_len = len, best_start = s;
      s += len;
    }
    if (best_len == 0) return false;
    mesh_.is_node[draft.vertices[(first_node + best_start + best_len / 2) % n]] = 1;
    ++report_.refined;
    return true;
  }

  // Splits a panel of too many nodes by a new rod: the node diagonal inside
  // the panel that halves the nodes most evenly, then the shortest; one that
  // cuts off a sliver (a part of less than 1% of the panel's (u,v) area) only
  // where there is no other. Nodes in a row along a straight trim (a shared
  // edge the join filled with the other face's nodes) made a "diagonal" along
  // the trim and a part of no area: a flat piece through three nodes in a
  // line, tilted any way (12.6 mm against walking_agent's bound of 12 on the
  // roof split along its diagonals).
  bool split(Draft& draft, const std::vector<int>& nodes, int origin) {
    const int k = static_cast<int>(nodes.size());
    const int n = static_cast<int>(draft.uv.size());
    // Twice the signed (u,v) area of the part from outline vertex a to b.
    auto part = [&](int a, int b) {
      double twice = 0;
      for (int c = a; c != b; c = (c + 1) % n) {
        const Vec2& p = draft.uv[c];
        const Vec2& q = draft.uv[(c + 1) % n];
        twice += p.x() * q.y() - p.y() * q.x();
      }
      return twice + draft.uv[b].x() * draft.uv[a].y() - draft.uv[b].y() * draft.uv[a].x();
    };
    double whole = 0;
    for (int c = 0; c < n; ++c)
      whole +=
          draft.uv[c].x() * draft.uv[(c + 1) % n].y() - draft.uv[c].y() * draft.uv[(c + 1) % n].x();
    whole = std::abs(whole);
    int best_i = -1, best_j = -1;
    bool best_sliver = true;
    bool best_long = false;  // at least min_node_spacing: no short new rod
    int best_balance = std::numeric_limits<int>::max();
    double best_length = std::numeric_limits<double>::infinity();
    for (int i = 0; i < k; ++i) {
      for (int j = i + 2; j < k; ++j) {
        if (i == 0 && j == k - 1) continue;  // neighbours in node order
        const int a = nodes[i], b = nodes[j];
        if (!diagonal_inside(draft.uv, a, b)) continue;
        const bool sliver = std::min(std::abs(part(a, b)), std::abs(part(b, a))) < 0.01 * whole;
        const int balance = std::abs((j - i) - (k - (j - i)));
        const double length = (original_[draft.vertices[a]] - original_[draft.vertices[b]]).norm();
        const bool long_enough = length >= params_.min_node_spacing;
        if (std::make_tuple(sliver, !long_enough, balance, length) <
            std::make_tuple(best_sliver, !best_long, best_balance, best_length)) {
          best_sliver = sliver, best_long = long_enough, best_balance = balance,
          best_length = length, best_i = a, best_j = b;
        }
      }
    }
    if (best_i < 0) return false;
    ++report_.split;
    for (const std::vector<int>& part :
         split_polygon(int(draft.vertices.size()), {{best_i, best_j}})) {
      Draft sub;
      for (int c : part) {
        sub.vertices.push_back(draft.vertices[c]);
        sub.uv.push_back(draft.uv[c]);
      }
      model(std::move(sub), origin);
    }
    return true;
  }

  // Bend lines for a panel of 4 or 5 nodes: of the node polygon's
  // triangulations whose diagonals run inside the panel, the one with the
  // smallest largest fold (ties: the first in node order, for determinism).
  // Under a hard bound, the one with the smallest fold among those whose
  // pieces hold it, if the smallest fold's do not: a pentagon of nodes has
  // no trim point to refine, and one triangulation over the bound (128 mm
  // against 100 on the roof's corner) made walking_agent walk the whole face
  // again at a bound 24% tighter (+18% panels).
  bool choose_bends(const Draft& draft, const std::vector<int>& nodes, std::vector<Diagonal>& out) {
    const int k = static_cast<int>(nodes.size());
    auto x = [&](int i) { return original_[draft.vertices[nodes[i % k]]]; };
    std::vector<std::pair<double, std::vector<Diagonal>>> candidates;
    // Fans from each node: k = 4 gives the two diagonals, k = 5 all five
    // triangulations of a pentagon.
    for (int i = 0; i < (k == 4 ? 2 : k); ++i) {
      std::vector<Diagonal> diagonals;
      bool inside = true;
      for (int j = i + 2; j <= i + k - 2; ++j) {
        const int a = nodes[i % k], b = nodes[j % k];
        if (!diagonal_inside(draft.uv, a, b)) inside = false;
        diagonals.push_back({std::min(a, b), std::max(a, b)});
      }
      if (!inside) continue;
      double fold = 0;
      for (int j = i + 1; j + 1 < i + k - 1; ++j) {
        const Vec3 n1 = triangle_normal(x(i), x(j), x(j + 1));
        const Vec3 n2 = triangle_normal(x(i), x(j + 1), x(j + 2));
        fold = std::max(fold, angle_between(n1, n2));
      }
      candidates.emplace_back(fold, std::move(diagonals));
    }
    if (candidates.empty()) return false;
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    out = candidates.front().second;
    if (params_.hard_bound && params_.max_deviation > 0 && candidates.size() > 1) {
      std::vector<Vec3> xyz;
      for (int v : draft.vertices) xyz.push_back(original_[v]);
      for (const auto& [fold, diagonals] : candidates) {
        (void)fold;
        if (node_triangles_deviation(draft, xyz, diagonals) <= params_.max_deviation) {
          out = diagonals;
          break;
        }
      }
    }
    return true;
  }

  // The plane of one piece: through its three nodes, or fitted to its points
  // through the nodes it has (fewer than three, or collinear).
  Plane piece_plane(const Draft& draft, const std::vector<Vec3>& xyz,
                    const std::vector<int>& piece) {
    std::vector<Vec3> nodes, points;
    for (int c : piece) {
      points.push_back(xyz[c]);
      if (is_node(mesh_, draft.vertices[c])) nodes.push_back(xyz[c]);
    }
    if (nodes.size() == 3) {
      const Vec3 n = triangle_normal(nodes[0], nodes[1], nodes[2]);
      const double scale =
          std::max({(nodes[1] - nodes[0]).squaredNorm(), (nodes[2] - nodes[0]).squaredNorm(),
                    (nodes[2] - nodes[1]).squaredNorm()});
      if (n.norm() > 1e-9 * scale) return {nodes[0], n.normalized()};
      // Collinear nodes: the line through the two farthest apart is fixed.
      std::size_t a = 0, b = 1;
      for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = i + 1; j < 3; ++j)
          if ((nodes[i] - nodes[j]).squaredNorm() > (nodes[a] - nodes[b]).squaredNorm())
            a = i, b = j;
      return fit_plane(points, {nodes[a], nodes[b]});
    }
    return fit_plane(points, nodes);
  }

  const SurfaceFace& face_;
  PanelMesh& mesh_;
  const BoundaryPiecesParams& params_;
  BoundaryPiecesReport& report_;
  const std::vector<Vec3>& original_;  // vertex positions on the surface, before any move
};

}  // namespace

BoundaryPiecesReport model_boundary_pieces(const SurfaceFace& face, PanelMesh& mesh,
                                           const BoundaryPiecesParams& params) {
  require_in_range("max_deviation", params.max_deviation, 0.0, 1e12);
  require_in_range("samples", params.samples, 1, 256);
  require_in_range("max_bends", params.max_bends, 1, 16);
  BoundaryPiecesReport report;
  // A trim point shared by two panels would be moved onto two planes: such a
  // point is kept where it is (a node for this stage's purposes).
  std::vector<int> uses(mesh.vertex_count(), 0);
  for (const auto& panel : mesh.panels)
    for (int v : panel) ++uses[v];
  if (mesh.is_node.empty()) mesh.is_node.assign(mesh.vertex_count(), 1);
  std::vector<char> shared_point(mesh.vertex_count(), 0);
  for (std::size_t v = 0; v < uses.size(); ++v)
    if (!mesh.is_node[v] && uses[v] > 1) shared_point[v] = mesh.is_node[v] = 1;

  // Each panel is modelled on its own: its trim points are its alone (a
  // shared one is a node here), so what a modeller writes to the mesh (its
  // trim points' positions, the ones it makes nodes) no other panel reads,
  // and the nodes it reads no modeller changes. The panels go to every
  // worker (the stage was a serial tenth of a trimmed face's panelize on
  // two threads); their panels, counts and reports are joined in panel
  // order, as one modeller would have made them.
  const std::vector<Vec3> original = mesh.xyz;
  struct Modelled {
    BoundaryPiecesReport report;
    std::vector<std::vector<int>> panels;
    std::vector<std::vector<Vec2>> corner_uv;
    std::vector<std::vector<Diagonal>> bends;
  };
  std::vector<Modelled> by_panel(mesh.panels.size());
  for_each_in_scopes(face, by_panel.size(), 8, [&](std::size_t k) {
    Modelled& out = by_panel[k];
    PieceModeller modeller(face, mesh, params, out.report, original);
    Draft draft{mesh.panels[k], panel_corner_uv(mesh, k)};
    if (modelled_as_pieces(mesh, k))
      modeller.model(std::move(draft), static_cast<int>(k));
    else
      modeller.keep(std::move(draft), static_cast<int>(k));
    out.panels = std::move(modeller.panels);
    out.corner_uv = std::move(modeller.corner_uv);
    out.bends = std::move(modeller.bends);
  });
  std::vector<std::vector<int>> panels;
  std::vector<std::vector<Vec2>> corner_uv;
  std::vector<std::vector<Diagonal>> bends;
  for (Modelled& m : by_panel) {
    for (auto& p : m.panels) panels.push_back(std::move(p));
    for (auto& c : m.corner_uv) corner_uv.push_back(std::move(c));
    for (auto& b : m.bends) bends.push_back(std::move(b));
    report.origin.insert(report.origin.end(), m.report.origin.begin(), m.report.origin.end());
    report.changed.insert(report.changed.end(), m.report.changed.begin(), m.report.changed.end());
    report.modelled += m.report.modelled;
    report.bends += m.report.bends;
    report.split += m.report.split;
    report.refined += m.report.refined;
  }
  for (std::size_t v = 0; v < shared_point.size(); ++v)
    if (shared_point[v]) mesh.is_node[v] = 0;

  const bool had_corner_uv = !mesh.corner_uv.empty();
  mesh.panels = std::move(panels);
  mesh.bends = std::move(bends);
  if (had_corner_uv) mesh.corner_uv = std::move(corner_uv);
  // A split or a new node made new rods.
  if (report.split > 0 || report.refined > 0) build_rods(mesh);
  return report;
}

}  // namespace tessella
