#include "faceset/shared_edge_nodes.h"

#include <BRepAdaptor_Surface.hxx>
#include <BRep_Tool.hxx>
#include <BndLib_Add2dCurve.hxx>
#include <Bnd_Box.hxx>
#include <Bnd_Box2d.hxx>
#include <Geom2d_Curve.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Vertex.hxx>
#include <algorithm>
#include <cmath>
#include <gp_Pnt2d.hxx>
#include <gp_Vec2d.hxx>
#include <limits>
#include <map>
#include <unordered_map>
#include <utility>

#include "common/parallel_chunks.h"
#include "geometry/edge_track.h"
#include "mesh/seam_sides.h"

namespace tessella {

namespace {

// A vertex of one face's mesh lying on the shared edge, at edge parameter t.
struct OnEdge {
  int vertex = -1;
  double t = 0;
};

// One node of the merged list: where it sits and which vertex stands for it
// on each side (-1: none yet).
struct EdgeNode {
  double t = 0;
  Vec3 xyz = Vec3::Zero();
  std::array<int, 2> vertex{-1, -1};
};

class EdgeSide {
 public:
  EdgeSide(const SharedEdge& e, int side, const SurfaceFace& face, PanelMesh& mesh)
      : curve_(e.pcurve[static_cast<std::size_t>(side)]),
        first_(e.first),
        last_(e.last),
        closed_(e.closed),
        face_(face),
        mesh_(mesh),
        box3d_(e.box) {
    // The curve's (u,v) box, grown by a little: most vertices are far from
    // the edge and skip the projection.
    BndLib_Add2dCurve::Add(curve_, first_, last_, 0.0, box_);
    double u0, v0, u1, v1;
    box_.Get(u0, v0, u1, v1);
    box_.Enlarge(1e-6 * std::max(u1 - u0, v1 - v0) + 1e-12);
  }

  // The edge parameter of vertex v if it lies on the edge (its 3D point
  // within `tol` of the edge's point on this face).
  bool locate(int v, double tol, double& t) const {
    const Vec2& q0 = mesh_.uv[static_cast<std::size_t>(v)];
    const Vec3& x = mesh_.xyz[static_cast<std::size_t>(v)];
    // Farther than tol from the edge's box: not on the edge, no projection
    // (most boundary vertices in the (u,v) box of a long edge).
    if (!box3d_.IsVoid()) {
      double x0, y0, z0, x1, y1, z1;
      box3d_.Get(x0, y0, z0, x1, y1, z1);
      const Vec3 out(std::max({x0 - x.x(), 0.0, x.x() - x1}),
                     std::max({y0 - x.y(), 0.0, x.y() - y1}),
                     std::max({z0 - x.z(), 0.0, x.z() - z1}));
      if (out.norm() > tol) return false;
    }
    // Where along the edge it may lie: its nearest chord of the edge's fine
    // 3D polyline. Farther than that polyline strays from the curve, plus
    // tol: not on the edge (for any (u,v) shift below). Else the projection
    // searches the parameters of that chord and its neighbours only: a
    // pcurve that ShapeFix approximated (hundreds of spans) made each
    // projection over the whole edge cost more than the face's metrics.
    if (!track_ready_) build_track(tol);
    std::size_t seg = 0;
    double along = 0;
    if (!track_.nearest(x, tol + reach_, seg, along)) return false;
    const double step = (last_ - first_) / double(track_.points().size() - 1);
    const double lo = std::max(first_, first_ + (double(seg) - 1) * step);
    const double hi = std::min(last_, first_ + (double(seg) + 2) * step);
    // On a periodic face the vertex may sit a period away from the curve.
    const double pu = face_.u_periodic() ? face_.u_period() : 0.0;
    const double pv = face_.v_periodic() ? face_.v_period() : 0.0;
    double best3d = std::numeric_limits<double>::infinity();
    for (double du : {0.0, pu, -pu}) {
      for (double dv : {0.0, pv, -pv}) {
        if ((du != 0 && pu == 0) || (dv != 0 && pv == 0)) continue;
        const gp_Pnt2d p(q0.x() + du, q0.y() + dv);
        if (box_.IsOut(p)) continue;
        double best = std::numeric_limits<double>::infinity(), at = first_;
        auto offer = [&](double s) {
          const double d = curve_->Value(s).Distance(p);
          if (d < best) best = d, at = s;
          return d;
        };
        offer(first_);
        offer(last_);
        // The nearest of a few samples over [lo, hi], then Newton on the
        // squared distance within it (the interval is three chords of a
        // polyline that follows the curve within tol: one minimum there).
        // OCCT's projection sampled and located spans anew on every call.
        // (Newton starts from the nearest sample inside: on a closed edge
        // `first_` may be as near, on the other side of [lo, hi].)
        constexpr int kSamples = 8;
        double s = lo, nearest = std::numeric_limits<double>::infinity();
        for (int i = 0; i <= kSamples; ++i) {
          const double si = lo + (hi - lo) * i / kSamples;
          const double d = offer(si);
          if (d < nearest) nearest = d, s = si;
        }
        try {
          for (int it = 0; it < 12; ++it) {
            gp_Pnt2d c;
            gp_Vec2d d1, d2;
            curve_->D2(s, c, d1, d2);
            const gp_Vec2d r(p, c);
            const double g = r.Dot(d1), h = d1.SquareMagnitude() + r.Dot(d2);
            if (!(h > 0)) break;
            const double next = std::clamp(s - g / h, lo, hi);
            const double moved = std::abs(next - s);
            s = next;
            if (moved <= 1e-14 * (std::abs(last_ - first_) + 1)) break;
          }
        } catch (const Standard_Failure&) {  // no second derivative: the samples
        }
        offer(s);
        const double d3 = (xyz_at(at) - x).norm();
        if (d3 < best3d) best3d = d3, t = at;
      }
    }
    if (best3d <= tol || !near_a_pole(q0)) return best3d <= tol;
    // A vertex at a pole of the face may carry any parameter along the
    // pole's iso-line (a sphere's pole at u = 0 where the edge runs at
    // u = pi/2): its (u,v) says nothing of where it is on the edge, so the
    // edge's 3D points over [lo, hi] are searched instead (the nearest of a
    // few samples, then a ternary search beside it). The same beside a
    // pole, where the nearest point in (u,v) is not the nearest in space (a
    // trim passing 0.8 mm from a sphere's pole: grid crossings a millimetre
    // from it were not found on the edge, and the other face's nodes not
    // put between them; bench_faces.random_face_set(1113)).
    constexpr int kSamples = 16;
    const double h = (hi - lo) / kSamples;
    double s = lo, nearest = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= kSamples; ++i) {
      const double si = lo + h * i;
      const double d = (xyz_at(si) - x).squaredNorm();
      if (d < nearest) nearest = d, s = si;
    }
    double a = std::max(lo, s - h), b = std::min(hi, s + h);
    for (int it = 0; it < 80 && b - a > 1e-15 * (std::abs(last_ - first_) + 1); ++it) {
      const double m0 = a + (b - a) / 3, m1 = b - (b - a) / 3;
      if ((xyz_at(m0) - x).squaredNorm() <= (xyz_at(m1) - x).squaredNorm())
        b = m1;
      else
        a = m0;
    }
    for (double si : {0.5 * (a + b), s}) {
      const double d3 = (xyz_at(si) - x).norm();
      if (d3 < best3d) best3d = d3, t = si;
    }
    return best3d <= tol;
  }
  // uv of the curve at t, shifted by whole periods to lie nearest `near`.
  Vec2 uv_near(double t, const Vec2& near) const {
    Vec2 q = uv_at(t);
    // A closed edge's two ends are one point in space but may be two in
    // (u,v): across a seam of a surface not flagged periodic (a B-spline
    // band closed on itself). The end nearer `near`, as a period shift does
    // on a periodic face (which keeps its shift below).
    const double eps = 1e-9 * std::abs(last_ - first_);
    if (closed_ && !face_.u_periodic() && !face_.v_periodic() &&
        (std::abs(t - first_) <= eps || std::abs(t - last_) <= eps)) {
      const Vec2 other = uv_at(std::abs(t - first_) <= eps ? last_ : first_);
      if ((other - near).norm() < (q - near).norm()) q = other;
    }
    if (face_.u_periodic()) {
      const double p = face_.u_period();
      q.x() += p * std::round((near.x() - q.x()) / p);
    }
    if (face_.v_periodic()) {
      const double p = face_.v_period();
      q.y() += p * std::round((near.y() - q.y()) / p);
    }
    return q;
  }
  // Whether q is beside a pole: one iso-line through it a hundred times
  // shorter than the other (within about R / 100 of a sphere's pole), and
  // the face's parameter range ends in a pole that way. (A face merely
  // parametrized unevenly, as many of OCCT's shell1, has no pole: searched
  // in space there, vertices of a micro edge's neighbour were taken onto
  // the edge, and a face was left 0.58% uncovered.)
  bool near_a_pole(const Vec2& q) const {
    const SurfacePoint d = face_.derivatives(q.x(), q.y());
    const double du = d.du.norm(), dv = d.dv.norm();
    const UvBounds b = face_.bounds();
    if (du <= 1e-2 * dv)  // u's iso-line short: a pole at an end of v
      return degenerate_at(Vec2(q.x(), b.v_min)) || degenerate_at(Vec2(q.x(), b.v_max));
    if (dv <= 1e-2 * du)
      return degenerate_at(Vec2(b.u_min, q.y())) || degenerate_at(Vec2(b.u_max, q.y()));
    return false;
  }
  // Whether the surface degenerates at q (a pole: all of an iso-line maps to
  // one point, so a vertex there may carry any parameter along it).
  bool degenerate_at(const Vec2& q) const {
    const SurfacePoint d = face_.derivatives(q.x(), q.y());
    const double du = d.du.norm(), dv = d.dv.norm();
    return du <= 1e-9 * dv || dv <= 1e-9 * du;
  }
  // The area on the surface between the edge's pcurve and the straight
  // (u,v) segment joining its points at ta and tb (a parabola's 2/3 of
  // chord x sagitta in (u,v), times the area element at the middle, tm).
  double uv_strip_area(double ta, double tb, double tm) const {
    const Vec2 a = uv_at(ta), b = uv_near(tb, a), m = uv_near(tm, a);
    const Vec2 chord = b - a;
    const double length = chord.norm();
    if (!(length > 0)) return 0.0;
    const Vec2 d = m - a;
    const double sagitta = std::abs(chord.x() * d.y() - chord.y() * d.x()) / length;
    const SurfacePoint s = face_.derivatives(m.x(), m.y());
    return 2.0 / 3.0 * length * sagitta * s.du.cross(s.dv).norm();
  }
  Vec2 uv_at(double t) const {
    const gp_Pnt2d c = curve_->Value(t);
    return {c.X(), c.Y()};
  }
  Vec3 xyz_at(double t) const {
    const Vec2 q = uv_at(t);
    return face_.point(q.x(), q.y());
  }

 private:
  // The edge's 3D polyline at uniform parameters, doubled until no chord's
  // midpoint is farther than tol from the curve (64 to 4096 chords); reach_:
  // how far the curve may stray from it (four times the largest midpoint
  // distance found, plus tol).
  void build_track(double tol) const {
    double sag = 0;
    std::vector<Vec3> line =
        sample_curve([this](double t) { return xyz_at(t); }, first_, last_, tol, 4096, sag);
    track_ = EdgeTrack(std::move(line));
    reach_ = 4 * sag + tol;
    track_ready_ = true;
  }
  mutable bool track_ready_ = false;
  mutable EdgeTrack track_;
  mutable double reach_ = 0;

  Handle(Geom2d_Curve) curve_;
  double first_, last_;
  bool closed_;
  const SurfaceFace& face_;
  PanelMesh& mesh_;
  Bnd_Box2d box_;
  Bnd_Box box3d_;
};

// Outline edges used by one panel only: the mesh's boundary (along trims).
struct SideHash {
  std::size_t operator()(const std::pair<int, int>& p) const {
    return std::hash<long long>()((static_cast<long long>(p.first) << 32) ^ p.second);
  }
};
// Panel sides and how many panels use them (only counted and looked up:
// a hash map gives the same flags as an ordered one).
using SideUse = std::unordered_map<std::pair<int, int>, int, SideHash>;

SideUse edge_use(const PanelMesh& mesh) {
  SideUse use;
  use.reserve(4 * mesh.panels.size());
  for (const auto& p : mesh.panels)
    for (std::size_t i = 0; i < p.size(); ++i) {
      const int a = p[i], b = p[(i + 1) % p.size()];
      ++use[{std::min(a, b), std::max(a, b)}];
    }
  return use;
}

// Whether the face has a seam edge (one edge on two sides of it).
bool has_seam(const TopoDS_Face& face) {
  for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next())
    if (BRep_Tool::IsClosed(TopoDS::Edge(ex.Current()), face)) return true;
  return false;
}

// Whether x is a corner of the face's outline: an end of an edge of the face
// that is not closed (a closed edge's own vertex is no corner where only it
// passes), a periodic face's seam not counted (no trim runs there).
bool corner_of_face(const TopoDS_Face& face, const SurfaceFace& surface, const Vec3& x,
                    double tol) {
  const bool periodic = surface.u_periodic() || surface.v_periodic();
  const gp_Pnt at(x.x(), x.y(), x.z());
  for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(ex.Current());
    if (BRep_Tool::Degenerated(edge) || (periodic && BRep_Tool::IsClosed(edge, face))) continue;
    TopoDS_Vertex v0, v1;
    TopExp::Vertices(edge, v0, v1);
    if (v0.IsNull() || v1.IsNull() || v0.IsSame(v1)) continue;
    for (const TopoDS_Vertex& v : {v0, v1})
      if (BRep_Tool::Pnt(v).Distance(at) <= std::max(tol, BRep_Tool::Tolerance(v))) return true;
  }
  return false;
}

void set_node(PanelMesh& mesh, int v) {
  if (mesh.is_node.empty()) return;  // every vertex is a node
  mesh.is_node[static_cast<std::size_t>(v)] = 1;
}

struct EdgeCounts {
  int nodes = 0, taken_over = 0;
};

// A merged node missing from a face's outline where that outline runs
// past it: the boundary side of one panel, from the node's neighbour in the
// chain (`from`), whose segment passes the node between its ends, within
// `tol` or the trim's bend. The node goes into that side. (The side ran on
// past the edge's end along the next edge of the face: OCCT's shell1, a
// 1.6 mm side of face 1 from x = 89.4 to 91 past the edge end at 90, where
// face 12's rods ended.)
bool insert_into_side(PanelMesh& m, const SurfaceFace& face, SideUse& use, int from, int node,
                      double tol) {
  const Vec3& x = m.xyz[static_cast<std::size_t>(node)];
  for (std::size_t p = 0; p < m.panels.size(); ++p) {
    std::vector<int>& panel = m.panels[p];
    const std::size_t n = panel.size();
    for (std::size_t i = 0; i < n; ++i) {
      const int a = panel[i], b = panel[(i + 1) % n];
      if ((a != from && b != from) || a == node || b == node) continue;
      const auto it = use.find({std::min(a, b), std::max(a, b)});
      if (it == use.end() || it->second != 1) continue;
      const Vec3& pa = m.xyz[static_cast<std::size_t>(a)];
      const Vec3 ab = m.xyz[static_cast<std::size_t>(b)] - pa;
      const double len2 = ab.squaredNorm();
      if (!(len2 > 0)) continue;
      const double w = (x - pa).dot(ab) / len2;
      // Off the side by the trim's bend between its ends at most (a chord
      // over two edges of the face: OCCT's shell1, 1.2e-3 mm on a 1 mm side).
      if (!(w > 0 && w < 1) || (pa + w * ab - x).norm() > std::max(tol, 0.01 * std::sqrt(len2)))
        continue;
      if (!m.corner_uv.empty()) {
        // Its (u,v) as this panel sees it: on the panel's side of a seam.
        std::vector<Vec2>& cuv = m.corner_uv[p];
        const Vec2 guess = (1 - w) * cuv[i] + w * cuv[(i + 1) % n];
        Vec2 uv = m.uv[static_cast<std::size_t>(node)];
        if (face.u_periodic()) uv.x() += seam_shift(guess.x(), uv.x(), face.u_period());
        if (face.v_periodic()) uv.y() += seam_shift(guess.y(), uv.y(), face.v_period());
        cuv.insert(cuv.begin() + static_cast<long>(i + 1), uv);
      }
      panel.insert(panel.begin() + static_cast<long>(i + 1), node);
      use.erase(it);
      ++use[{std::min(a, node), std::max(a, node)}];
      ++use[{std::min(node, b), std::max(node, b)}];
      return true;
    }
  }
  return false;
}

// Along the shared edge the face's outline should run from merged node to
// merged node. Where it runs past a node instead (a side from the node's
// neighbour on to a point beyond the edge's end), the node goes into that
// side (insert_into_side). Other misses stay, and the check of the joined
// result (faceset/shared_edge_check.h) counts them and warns.
void insert_nodes_run_past(const SharedEdge& e, int s, PanelMesh& m, const SurfaceFace& face,
                           const std::vector<EdgeNode>& nodes) {
  const std::size_t n = nodes.size();
  const std::size_t segments = e.closed ? (n > 2 ? n : 0) : (n > 0 ? n - 1 : 0);
  if (segments == 0) return;
  auto vertex = [&](std::size_t k) { return nodes[k % n].vertex[static_cast<std::size_t>(s)]; };
  // The sides of the panels at the nodes (the others cannot hold a segment).
  std::vector<char> at_node(m.vertex_count(), 0);
  for (std::size_t k = 0; k < n; ++k) at_node[static_cast<std::size_t>(vertex(k))] = 1;
  SideUse use;
  for (const auto& panel : m.panels) {
    if (std::none_of(panel.begin(), panel.end(),
                     [&](int v) { return at_node[static_cast<std::size_t>(v)] != 0; }))
      continue;
    for (std::size_t i = 0; i < panel.size(); ++i) {
      const int a = panel[i], b = panel[(i + 1) % panel.size()];
      ++use[{std::min(a, b), std::max(a, b)}];
    }
  }
  const double tol = 10e-6 * face.model_size();
  for (std::size_t k = 0; k < segments; ++k) {
    const int a = vertex(k), b = vertex(k + 1);
    if (use.count({std::min(a, b), std::max(a, b)}) == 0 &&
        !insert_into_side(m, face, use, a, b, tol))
      insert_into_side(m, face, use, b, a, tol);
  }
}

// One shared edge: its two faces' vertices on it merged into one list of
// nodes, each face's mesh made to use them; the strips' areas added to its
// faces' strip_area.
void conform_edge(const FaceSet::Impl& set, const SharedEdge& e, std::vector<PanelMesh*>& meshes,
                  double merge_distance, std::vector<double>& strip_area, EdgeCounts& counts) {
  std::array<PanelMesh*, 2> mesh{meshes[static_cast<std::size_t>(e.faces[0])],
                                 meshes[static_cast<std::size_t>(e.faces[1])]};
  std::array<const SurfaceFace*, 2> face{set.faces[static_cast<std::size_t>(e.faces[0])].get(),
                                         set.faces[static_cast<std::size_t>(e.faces[1])].get()};
  const std::array<EdgeSide, 2> side{EdgeSide(e, 0, *face[0], *mesh[0]),
                                     EdgeSide(e, 1, *face[1], *mesh[1])};
  const double tol = 1e-6 * std::max(face[0]->model_size(), face[1]->model_size());
  const double span = e.last - e.first;
  // The vertices of each face on the edge: its boundary vertices that lie on it.
  std::array<std::vector<OnEdge>, 2> on;
  std::array<std::unordered_map<int, double>, 2> t_of;  // looked up only
  std::array<SideUse, 2> uses;                          // each side's panel sides
  for (int s = 0; s < 2; ++s) {
    const PanelMesh& m = *mesh[static_cast<std::size_t>(s)];
    std::vector<char> boundary(m.vertex_count(), 0);
    uses[static_cast<std::size_t>(s)] = edge_use(m);
    for (const auto& [edge, count] : uses[static_cast<std::size_t>(s)])
      if (count == 1)
        boundary[static_cast<std::size_t>(edge.first)] =
            boundary[static_cast<std::size_t>(edge.second)] = 1;
    for (int v = 0; v < static_cast<int>(m.vertex_count()); ++v) {
      double t = 0;
      if (!boundary[static_cast<std::size_t>(v)] ||
          !side[static_cast<std::size_t>(s)].locate(v, tol, t))
        continue;
      on[static_cast<std::size_t>(s)].push_back({v, t});
      t_of[static_cast<std::size_t>(s)][v] = t;
    }
  }
  // The merged list of nodes: sorted along the edge; nodes of the two sides
  // closer than merge_distance joined, so no short rod crosses between
  // them; an edge end wins, else side 0. Two nodes of one side stay two
  // (unless they coincide): that face's own rod between them was kept by its
  // pipeline, a trim node beside an edge end, and merging them bent its
  // panel out of the deviation bound (walking_agent on the split roof: a
  // 121 mm side merged away, 52 mm against a bound of 30).
  struct Entry {
    double t;
    int side, vertex;
    Vec3 xyz;
  };
  // Nodes, and an outline vertex at an end of the edge even where its
  // face's method left it a trim point (a B-rep vertex where the edge
  // meets a free trim): the other face may have a node there, and a trim
  // point's boundary piece, modelled flat between its nodes, moved it off
  // the trim (the roof split along its diagonals, where a diagonal meets
  // the drum: 9.9 mm, and a segment of the edge bounded panels of one face
  // only). In 3D: such a vertex is located a hair inside the edge's
  // parameter range, farther than at_end allows.
  // A closed edge's vertex is a corner only where another edge of either
  // face (a trim) meets it: a cylinder's rim where only the seam passes is
  // none, and made a node it left a 14.8 mm rod beside a node of the rim
  // (boundary_driven on a revolved profile and its top,
  // bench_faces.random_face_set(232)).
  const bool ends_are_corners = !e.closed ||
                                corner_of_face(set.occt[static_cast<std::size_t>(e.faces[0])],
                                               *face[0], side[0].xyz_at(e.first), tol) ||
                                corner_of_face(set.occt[static_cast<std::size_t>(e.faces[1])],
                                               *face[1], side[1].xyz_at(e.first), tol);
  std::vector<Entry> entries;
  for (int s = 0; s < 2; ++s) {
    const PanelMesh& m = *mesh[static_cast<std::size_t>(s)];
    const Vec3 ends[2] = {side[static_cast<std::size_t>(s)].xyz_at(e.first),
                          side[static_cast<std::size_t>(s)].xyz_at(e.last)};
    auto at_an_end = [&](int v) {
      const Vec3& x = m.xyz[static_cast<std::size_t>(v)];
      return ends_are_corners && ((x - ends[0]).norm() <= tol || (x - ends[1]).norm() <= tol);
    };
    for (const OnEdge& o : on[static_cast<std::size_t>(s)])
      if (is_node(m, o.vertex) || at_an_end(o.vertex))
        entries.push_back(
            {o.t, s, o.vertex,
             mesh[static_cast<std::size_t>(s)]->xyz[static_cast<std::size_t>(o.vertex)]});
  }
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.t < b.t || (a.t == b.t && a.side < b.side);
  });
  const double join = std::max(merge_distance, tol);
  auto at_end = [&](double t) {
    return std::abs(t - e.first) <= 1e-9 * std::abs(span) ||
           std::abs(t - e.last) <= 1e-9 * std::abs(span);
  };
  std::vector<EdgeNode> nodes;
  // First the entries that coincide (within tol) become one group each;
  // then a group of one side only joins a neighbouring group of the other
  // side only closer than `join`, the nearest pairs first. (Joining
  // greedily along the edge paired each vertex of one face with the next
  // of the other where both had a row of vertices, one of them an extra
  // line's: the pairs that coincided came apart and two nodes sat at one
  // position; walking_agent on the centre split at 12 mm.)
  // An edge end is a node on both sides (a B-rep vertex where faces meet,
  // made one even where a face's method left it a trim point); a node of
  // either side within a hundredth of the merge distance of it is that
  // node: left two, they made a rod of a tenth of a millimetre
  // (walking_agent where two cut planes cross on a B-spline face,
  // bench_faces.random_face_set(220): 0.096 mm against a 59 mm minimum).
  const double snap = std::max(tol, 0.01 * merge_distance);
  auto one_node = [&](const Entry& x, const Entry& g) {
    const double d = (x.xyz - g.xyz).norm();
    return d <= tol || (ends_are_corners && d <= snap && (at_end(x.t) || at_end(g.t)));
  };
  std::vector<std::vector<const Entry*>> members;
  for (const Entry& x : entries) {
    if (!members.empty() && one_node(x, *members.back().front()))
      members.back().push_back(&x);
    else
      members.push_back({&x});
  }
  // A closed edge: the last group may be the first one again (its two ends).
  if (e.closed && members.size() > 1 &&
      std::all_of(members.back().begin(), members.back().end(), [&](const Entry* x) {
        return (x->xyz - members.front().front()->xyz).norm() <= tol;
      })) {
    for (const Entry* x : members.back()) members.front().push_back(x);
    members.pop_back();
  }
  auto one_side = [](const std::vector<const Entry*>& g) {
    for (const Entry* x : g)
      if (x->side != g.front()->side) return -1;
    return g.front()->side;
  };
  const std::size_t groups = members.size();
  std::vector<std::pair<double, std::size_t>> pairs;  // (distance, first of the pair)
  for (std::size_t k = 0; k + 1 < groups + (e.closed && groups > 2 ? 1 : 0); ++k) {
    const auto& g0 = members[k];
    const auto& g1 = members[(k + 1) % groups];
    const int s0 = one_side(g0), s1 = one_side(g1);
    if (s0 < 0 || s1 < 0 || s0 == s1) continue;
    const double d = (g0.front()->xyz - g1.front()->xyz).norm();
    if (d <= join) pairs.push_back({d, k});
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<char> paired(groups, 0), gone(groups, 0);
  for (const auto& [d, k] : pairs) {
    const std::size_t k1 = (k + 1) % groups;
    if (paired[k] || paired[k1]) continue;
    paired[k] = paired[k1] = 1;
    for (const Entry* x : members[k1]) members[k].push_back(x);
    gone[k1] = 1;
  }
  {
    std::vector<std::vector<const Entry*>> kept;
    for (std::size_t k = 0; k < groups; ++k)
      if (!gone[k]) kept.push_back(std::move(members[k]));
    members = std::move(kept);
  }
  // Where two nodes join, the one kept: an edge end's, else that of the
  // side whose panels a move would bend. A planar face's panels stay flat
  // wherever their nodes go along the edge, a curved face's do not: a
  // cylinder's node moved onto its planar cap's took a panel 27% over
  // walking_agent's bound, try after try (a box fused with a cylinder,
  // bench_faces.random_face_set(154)). Else side 0's.
  auto planar = [&](int s) {
    return BRepAdaptor_Surface(
               set.occt[static_cast<std::size_t>(e.faces[static_cast<std::size_t>(s)])], false)
               .GetType() == GeomAbs_Plane;
  };
  const int kept_side = planar(0) && !planar(1) ? 1 : 0;
  for (const auto& group : members) {
    const Entry* pick = group.front();
    for (const Entry* x : group)
      if (at_end(x->t) && !at_end(pick->t)) pick = x;
    if (!at_end(pick->t))
      for (const Entry* x : group)
        if (x->side == kept_side) {
          pick = x;
          break;
        }
    EdgeNode n;
    n.t = pick->t;
    n.xyz = pick->xyz;
    nodes.push_back(n);
  }
  counts.nodes += static_cast<int>(nodes.size());
  // The strips between the edge and its chords, node to node.
  for (std::size_t k = 0; k + 1 < nodes.size() + (e.closed ? 1 : 0); ++k) {
    const EdgeNode& a = nodes[k];
    const EdgeNode& b = nodes[(k + 1) % nodes.size()];
    double tm = 0.5 * (a.t + b.t);
    if (e.closed && k + 1 == nodes.size()) tm = 0.5 * (a.t + b.t + span);
    if (tm > e.last) tm -= span;
    const Vec3 chord = b.xyz - a.xyz;
    if (!(chord.norm() > 0)) continue;
    for (int s = 0; s < 2; ++s) {
      const EdgeSide& es = side[static_cast<std::size_t>(s)];
      const Vec3 m = es.xyz_at(tm) - a.xyz;
      const double sagitta = (m - chord * (m.dot(chord) / chord.squaredNorm())).norm();
      // The coverage measures in (u,v), where the panel's side is straight
      // between the nodes and the edge's pcurve may bend more than the
      // edge does in space: a plane's section of a B-spline face, a 3D arc
      // of 0.8 mm sagitta whose strip in (u,v) came to 3.2 times the 3D
      // estimate (bench_faces.random_face_set(175): a small triangular face
      // refused, 0.53% uncovered). The larger of the two.
      strip_area[static_cast<std::size_t>(e.faces[static_cast<std::size_t>(s)])] +=
          std::max(2.0 / 3.0 * chord.norm() * sagitta, es.uv_strip_area(a.t, b.t, tm));
    }
  }

  for (int s = 0; s < 2; ++s) {
    PanelMesh& m = *mesh[static_cast<std::size_t>(s)];
    // On a periodic face a vertex moved onto a node has one (u,v), on one
    // side of the seam; a panel on the other side needs its own: each
    // panel keeps its corners' (u,v) from here on (without them a seam
    // panel spanned the whole period in (u,v) and the coverage check
    // found a hole the width of the face).
    // So on a face with a seam whose surface is not periodic (a B-spline
    // band closed on itself: the seam's two sides are two (u,v) lines; OCCT's
    // Pump_TopCover took 47% "overlap" once both of its rims took nodes).
    const std::size_t fs = static_cast<std::size_t>(e.faces[static_cast<std::size_t>(s)]);
    if (m.corner_uv.empty() &&
        (face[static_cast<std::size_t>(s)]->u_periodic() ||
         face[static_cast<std::size_t>(s)]->v_periodic() || has_seam(set.occt[fs]))) {
      m.corner_uv.reserve(m.panels.size());
      for (std::size_t p = 0; p < m.panels.size(); ++p)
        m.corner_uv.push_back(panel_corner_uv(m, p));
    }
    // Each merged node's vertex on this side: the first of its own there
    // (moved onto the node), else a new one; its other ones join it.
    std::map<int, int> replace;    // vertex -> the vertex standing for its node
    std::map<int, Vec2> moved_uv;  // vertices moved onto a merged node
    // Where this side's vertices moved onto a merged node lay on the edge
    // before: a run's direction is read from these (below).
    std::unordered_map<int, double> t_before;  // looked up only
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      EdgeNode& n = nodes[k];
      int& mine = n.vertex[static_cast<std::size_t>(s)];
      for (const Entry* x : members[k]) {
        if (x->side != s) continue;
        if (mine < 0)
          mine = x->vertex;
        else
          replace[x->vertex] = mine;
      }
      if (mine < 0) {
        mine = static_cast<int>(m.vertex_count());
        m.uv.push_back(side[static_cast<std::size_t>(s)].uv_at(n.t));
        m.xyz.push_back(n.xyz);
        if (!m.is_node.empty()) m.is_node.push_back(1);
        ++counts.taken_over;
      } else if (m.xyz[static_cast<std::size_t>(mine)] != n.xyz) {
        moved_uv[mine] = m.uv[static_cast<std::size_t>(mine)];
        m.uv[static_cast<std::size_t>(mine)] = side[static_cast<std::size_t>(s)].uv_at(n.t);
        m.xyz[static_cast<std::size_t>(mine)] = n.xyz;
        ++counts.taken_over;
      }
      set_node(m, mine);
      auto& t_here = t_of[static_cast<std::size_t>(s)];
      const auto was = t_here.find(mine);
      if (was != t_here.end() && was->second != n.t) t_before.emplace(mine, was->second);
      t_here[mine] = n.t;
    }
    // A trim point of this side where a node now sits (the other side's
    // node, or one of its own moved there) is that node: left a vertex of
    // its own, the outline ran node, trim point, node at one position
    // (iso_grid on the roof split along its diagonals at 900 mm: a grid
    // corner on a diagonal, a node of face 2 and a trim point of face 3,
    // whose node 180 mm away merged onto it).
    std::vector<char> stands(m.vertex_count(), 0);  // a node's vertex on this side
    for (const EdgeNode& n : nodes)
      stands[static_cast<std::size_t>(n.vertex[static_cast<std::size_t>(s)])] = 1;
    for (const OnEdge& o : on[static_cast<std::size_t>(s)]) {
      if (stands[static_cast<std::size_t>(o.vertex)] || replace.count(o.vertex)) continue;
      const Vec3& x = m.xyz[static_cast<std::size_t>(o.vertex)];
      for (const EdgeNode& n : nodes)
        if ((n.xyz - x).norm() <= tol) {
          replace[o.vertex] = n.vertex[static_cast<std::size_t>(s)];
          break;
        }
    }
    const auto& use = uses[static_cast<std::size_t>(s)];
    auto on_edge = [&](int v) { return t_of[static_cast<std::size_t>(s)].count(v) != 0; };
    // An outline side along the edge: both ends on it, on the mesh boundary,
    // its middle near the edge's point halfway (not a chord across a bend).
    auto along = [&](int a, int b, const Vec2& ua, const Vec2& ub) {
      if (!on_edge(a) || !on_edge(b)) return false;
      const auto it = use.find({std::min(a, b), std::max(a, b)});
      if (it == use.end() || it->second != 1) return false;
      const double ta = t_of[static_cast<std::size_t>(s)][a];
      const double tb = t_of[static_cast<std::size_t>(s)][b];
      double halfway = 0.5 * (ta + tb);
      if (e.closed && std::abs(ta - tb) > 0.5 * std::abs(span)) {  // across the closing point
        halfway += 0.5 * span;
        if (halfway > e.last) halfway -= span;
      }
      const EdgeSide& es = side[static_cast<std::size_t>(s)];
      auto follows = [&](const Vec2& pa, const Vec2& pb) {
        const Vec2 mid = 0.5 * (pa + pb);
        return (es.uv_near(halfway, mid) - mid).norm() <= 0.25 * (pa - pb).norm();
      };
      if (follows(ua, ub)) return true;
      // An end at a pole carries whatever parameter its face's method gave
      // it there, not the edge's: compare with the edge's own (u,v) at that
      // end. (A box's filleted corner, a sphere whose pole is where the
      // edge meets two others: the side from the pole looked like a chord
      // across the face, and the other face's node on it was missed: a
      // T-junction, walking_agent on bench_faces.random_face_set(11).)
      const bool pole_a = es.degenerate_at(ua), pole_b = es.degenerate_at(ub);
      if (pole_a || pole_b) {
        const Vec2 pa = pole_a ? es.uv_near(ta, ub) : ua;
        const Vec2 pb = pole_b ? es.uv_near(tb, pa) : ub;
        if (follows(pa, pb)) return true;
      }
      // The same test in space. Near a pole the edge's pcurve turns through
      // a large angle within a few millimetres, and a side between two of
      // its points looks like a chord across the face in (u,v) while it
      // follows the edge in space (a sphere cut 0.8 mm from its pole:
      // trim points kept between two nodes, a T-junction;
      // bench_faces.random_face_set(1113)).
      const Vec3& xa = m.xyz[static_cast<std::size_t>(a)];
      const Vec3& xb = m.xyz[static_cast<std::size_t>(b)];
      const Vec3 mid = 0.5 * (xa + xb);
      return (es.xyz_at(halfway) - mid).norm() <= 0.25 * (xa - xb).norm();
    };
    // Per-panel corner (u,v)s are kept (a periodic face's seam corners).
    const bool corner_uv = !m.corner_uv.empty();
    // The vertices on this edge (t_of's): a panel with none of them, and no
    // corner repeated, comes out of the walk below as it went in.
    std::vector<char> on_this_edge(m.vertex_count(), 0);
    for (const auto& [v, t] : t_of[static_cast<std::size_t>(s)])
      on_this_edge[static_cast<std::size_t>(v)] = 1;
    for (std::size_t p = 0; p < m.panels.size(); ++p) {
      std::vector<int>& panel = m.panels[p];
      const std::size_t n = panel.size();
      bool untouched = true;
      for (std::size_t i = 0; i < n && untouched; ++i)
        untouched =
            !on_this_edge[static_cast<std::size_t>(panel[i])] && panel[i] != panel[(i + 1) % n];
      if (untouched) continue;
      std::vector<Vec2> cuv = panel_corner_uv(m, p);
      // A corner moved onto a merged node: its (u,v) follows, on its own side
      // of a seam.
      for (std::size_t i = 0; i < n; ++i) {
        const auto mv = moved_uv.find(panel[i]);
        if (mv != moved_uv.end())
          cuv[i] = side[static_cast<std::size_t>(s)].uv_near(
              t_of[static_cast<std::size_t>(s)][panel[i]], cuv[i]);
      }
      std::vector<char> seg(n, 0);  // side i (i -> i+1) runs along the edge
      bool any = false;
      for (std::size_t i = 0; i < n; ++i)
        any |= (seg[i] = along(panel[i], panel[(i + 1) % n], cuv[i], cuv[(i + 1) % n])) != 0;
      std::vector<int> out;
      std::vector<Vec2> out_uv;
      // Start the walk at a corner that begins a run (not inside one).
      std::size_t start = 0;
      while (any && start < n && !(seg[start] && !seg[(start + n - 1) % n])) ++start;
      // Parameter distance from `from` to `to` along the edge, going up or
      // down it (round a closed edge: in [0, span)).
      auto ahead = [&](double from, double to, bool up) {
        const double d = up ? to - from : from - to;
        return e.closed ? std::fmod(std::fmod(d, span) + span, span) : d;
      };
      if (any && start == n && e.closed) {
        // Every side along the closed edge (one panel covering a disc whose
        // rim is the edge): the outline is every merged node in order round
        // the loop, the way corner 0 goes to corner 1.
        const double t0 = t_of[static_cast<std::size_t>(s)][panel[0]];
        const bool up =
            ahead(t0, t_of[static_cast<std::size_t>(s)][panel[1 % n]], true) < 0.5 * span;
        std::vector<std::pair<double, std::size_t>> round;
        for (std::size_t k = 0; k < nodes.size(); ++k)
          round.push_back({ahead(t0, nodes[k].t, up), k});
        std::sort(round.begin(), round.end());
        Vec2 near = cuv[0];
        for (const auto& [key, k] : round) {
          out.push_back(nodes[k].vertex[static_cast<std::size_t>(s)]);
          near = side[static_cast<std::size_t>(s)].uv_near(nodes[k].t, near);
          out_uv.push_back(near);
        }
      } else if (!any || start == n) {  // nothing along the edge
        out = panel;
        out_uv = cuv;
      }
      std::size_t i = start;
      for (std::size_t step = 0; any && start < n && step < n;) {
        if (!seg[i]) {
          out.push_back(panel[i]);
          out_uv.push_back(cuv[i]);
          i = (i + 1) % n, ++step;
          continue;
        }
        // A run of sides along the edge from corner i to corner j.
        std::size_t j = i, len = 0;
        while (seg[j] && len < n) j = (j + 1) % n, ++len;
        const int a = panel[i], b = panel[j];
        const double ta = t_of[static_cast<std::size_t>(s)][a];
        const double tb = t_of[static_cast<std::size_t>(s)][b];
        out.push_back(a);
        out_uv.push_back(cuv[i]);
        // The merged nodes strictly between, in the run's direction: that of
        // its middle corner (not its second: a crossing snapped onto the
        // curve may lie just past the next trim point); node to node, the
        // shorter way round a closed edge.
        // Inner corners that stand for the run's end nodes say nothing:
        // several curves ending at one edge end leave coincident vertices
        // there (located a hair apart), and a run [end, its twin, node]
        // went "up" from the end by the twin and skipped the nodes between
        // (boundary_driven, the roof split along its diagonals, at the drum).
        auto stands_for = [&](int v) {
          const auto r = replace.find(v);
          return r != replace.end() ? r->second : v;
        };
        // The direction is read where the run's corners lay before the
        // merge: a corner moved onto the other side's node up to a merge
        // distance away can pass its own trim points, which then lie behind
        // it, and their middle pointed the wrong way: the run took every
        // node round a closed edge (boundary_driven, an extruded closed
        // curve's cap, bench_faces.random_face_set(48): a corner moved
        // 400 mm, 91% overlap).
        auto before = [&](int v) {
          const auto it = t_before.find(v);
          return it != t_before.end() ? it->second : t_of[static_cast<std::size_t>(s)][v];
        };
        const double ta0 = before(a), tb0 = before(b);
        std::vector<double> inner;
        for (std::size_t k = 1; k < len; ++k) {
          const int v = panel[(i + k) % n];
          if (stands_for(v) != stands_for(a) && stands_for(v) != stands_for(b))
            inner.push_back(before(v));
        }
        bool up = tb0 > ta0;
        if (!inner.empty()) {
          const double tm = inner[(inner.size() + 1) / 2 - 1];  // the run's middle
          up = e.closed ? ahead(ta0, tm, true) < ahead(ta0, tb0, true) : tm > ta0;
        } else if (e.closed) {
          up = ahead(ta0, tb0, true) < 0.5 * span;
        }
        const double reach = ahead(ta, tb, up);
        std::vector<std::pair<double, std::size_t>> between;
        for (std::size_t k = 0; k < nodes.size(); ++k) {
          const int v = nodes[k].vertex[static_cast<std::size_t>(s)];
          if (v == a || v == b) continue;
          const double d = ahead(ta, nodes[k].t, up);
          if (d > 0 && d < reach) between.push_back({d, k});
        }
        std::sort(between.begin(), between.end());
        for (const auto& [key, k] : between) {
          out.push_back(nodes[k].vertex[static_cast<std::size_t>(s)]);
          out_uv.push_back(side[static_cast<std::size_t>(s)].uv_near(nodes[k].t, out_uv.back()));
        }
        step += len;
        i = j;
      }
      // Joined nodes: the one standing for them; repeated corners once.
      std::vector<int> clean;
      std::vector<Vec2> clean_uv;
      for (std::size_t k = 0; k < out.size(); ++k) {
        const auto r = replace.find(out[k]);
        const int w = r != replace.end() ? r->second : out[k];
        if (!clean.empty() && clean.back() == w) continue;
        clean.push_back(w);
        clean_uv.push_back(out_uv[k]);
      }
      while (clean.size() > 1 && clean.front() == clean.back())
        clean.pop_back(), clean_uv.pop_back();
      panel = std::move(clean);
      if (corner_uv) m.corner_uv[p] = std::move(clean_uv);
    }
    for (std::size_t p = m.panels.size(); p-- > 0;) {
      if (m.panels[p].size() >= 3) continue;
      m.panels.erase(m.panels.begin() + static_cast<long>(p));
      if (corner_uv) m.corner_uv.erase(m.corner_uv.begin() + static_cast<long>(p));
    }
    // Vertices left unused stay until all edges are done (indices stable).
  }
  for (int s = 0; s < 2; ++s)
    insert_nodes_run_past(e, s, *mesh[static_cast<std::size_t>(s)],
                          *face[static_cast<std::size_t>(s)], nodes);
}

// The edges in rounds: an edge goes one round after the last earlier edge
// (in the set's order) that shares a face with it. An edge changes its two
// faces' meshes only and evaluates their surfaces (each face has its own
// copy, FaceSet::from_brep_string), so the edges of a round can run side by
// side, and each face still sees its edges one after the other in the set's
// order: the same meshes and strip areas as one edge at a time.
std::vector<std::vector<std::size_t>> edge_rounds(const FaceSet::Impl& set) {
  std::vector<std::size_t> next_round(set.faces.size(), 0);  // per face
  std::vector<std::vector<std::size_t>> rounds;
  for (std::size_t k = 0; k < set.shared.size(); ++k) {
    const auto f0 = static_cast<std::size_t>(set.shared[k].faces[0]);
    const auto f1 = static_cast<std::size_t>(set.shared[k].faces[1]);
    const std::size_t round = std::max(next_round[f0], next_round[f1]);
    if (round == rounds.size()) rounds.emplace_back();
    rounds[round].push_back(k);
    next_round[f0] = next_round[f1] = round + 1;
  }
  return rounds;
}

}  // namespace

SharedEdgeReport conform_shared_edges(const FaceSet::Impl& set, std::vector<PanelMesh*>& meshes,
                                      double merge_distance) {
  SharedEdgeReport report;
  report.strip_area.assign(meshes.size(), 0.0);
  std::vector<EdgeCounts> counts(set.shared.size());
  const int threads = worker_threads();
  for (const std::vector<std::size_t>& round : edge_rounds(set)) {
    ChunkQueue queue(round.size(), 1);
    run_chunks(queue, threads, [&](bool) {
      std::size_t begin = 0, end = 0;
      while (queue.next(begin, end))
        for (std::size_t k = begin; k < end; ++k)
          conform_edge(set, set.shared[round[k]], meshes, merge_distance, report.strip_area,
                       counts[round[k]]);
    });
  }
  for (const EdgeCounts& c : counts) report.nodes += c.nodes, report.taken_over += c.taken_over;
  // Unused vertices go (indices were kept stable while the edges ran).
  ChunkQueue faces(meshes.size(), 1);
  run_chunks(faces, threads, [&](bool) {
    std::size_t begin = 0, end = 0;
    while (faces.next(begin, end))
      for (std::size_t f = begin; f < end; ++f) {
        remove_unused_vertices(*meshes[f]);
        build_rods(*meshes[f]);
      }
  });
  return report;
}

}  // namespace tessella
