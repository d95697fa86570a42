#include "tessella/shape_export.h"

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom_BezierSurface.hxx>
#include <ShapeFix_ShapeTolerance.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Wire.hxx>
#include <algorithm>
#include <gp_Pln.hxx>
#include <map>
#include <sstream>
#include <unordered_map>

#include "tessella/errors.h"
#include "mesh/panel_model.h"
#include "tessella/progress.h"

namespace tessella {

namespace {

gp_Pnt pnt(const Vec3& v) { return gp_Pnt(v.x(), v.y(), v.z()); }

std::string to_brep(const TopoDS_Shape& shape) {
  std::ostringstream out;
  BRepTools::Write(shape, out);
  return out.str();
}

// Normal of the polygon by Newell's method (follows the corner order).
Vec3 newell_normal(const std::vector<Vec3>& p) {
  Vec3 n = Vec3::Zero();
  for (std::size_t k = 0; k < p.size(); ++k) n += p[k].cross(p[(k + 1) % p.size()]);
  return n;
}

// Largest distance of the corners from the plane through their mean with
// the given normal (unit).
double off_plane(const std::vector<Vec3>& p, const Vec3& c, const Vec3& n) {
  double worst = 0;
  for (const Vec3& q : p) worst = std::max(worst, std::abs((q - c).dot(n)));
  return worst;
}

// One vertex per mesh vertex and one straight edge per vertex pair, shared by
// every panel (and piece) that uses them: neighbouring panels meet on one
// edge, and the compound is about a third smaller to write and to read than
// one of independent faces (bench/document_speed.py).
class SharedTopology {
 public:
  explicit SharedTopology(const PanelMesh& mesh) : mesh_(mesh) {}

  // The edge from vertex a to vertex b, oriented a -> b. Its curve runs from
  // the smaller index (parameter 0) to the larger (parameter = its length).
  // Throws NotShareable when the two points coincide.
  TopoDS_Edge edge(int a, int b) {
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    auto it = edges_.find(key);
    if (it == edges_.end()) {
      BRepBuilderAPI_MakeEdge make(vertex(key.first), vertex(key.second));
      if (!make.IsDone()) throw NotShareable();
      it = edges_.emplace(key, make.Edge()).first;
    }
    return a == key.first ? it->second : TopoDS::Edge(it->second.Reversed());
  }

  // The closed wire through the vertices, in order.
  TopoDS_Wire wire(const std::vector<int>& ids) {
    BRep_Builder builder;
    TopoDS_Wire w;
    builder.MakeWire(w);
    for (std::size_t k = 0; k < ids.size(); ++k)
      builder.Add(w, edge(ids[k], ids[(k + 1) % ids.size()]));
    w.Closed(Standard_True);
    return w;
  }

  struct NotShareable {};

 private:
  const TopoDS_Vertex& vertex(int v) {
    auto it = vertices_.find(v);
    if (it == vertices_.end())
      it = vertices_.emplace(v, BRepBuilderAPI_MakeVertex(pnt(mesh_.xyz[v])).Vertex()).first;
    return it->second;
  }

  const PanelMesh& mesh_;
  std::unordered_map<int, TopoDS_Vertex> vertices_;
  std::map<std::pair<int, int>, TopoDS_Edge> edges_;
};

// Raises (never lowers: the edges are shared) the tolerance of the wire's
// edges and vertices to `tolerance`.
void raise_tolerance(const TopoDS_Wire& wire, double tolerance) {
  BRep_Builder builder;
  for (TopExp_Explorer e(wire, TopAbs_EDGE); e.More(); e.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
    if (BRep_Tool::Tolerance(edge) < tolerance) builder.UpdateEdge(edge, tolerance);
  }
  for (TopExp_Explorer v(wire, TopAbs_VERTEX); v.More(); v.Next()) {
    const TopoDS_Vertex& vertex = TopoDS::Vertex(v.Current());
    if (BRep_Tool::Tolerance(vertex) < tolerance) builder.UpdateVertex(vertex, tolerance);
  }
}

// A flat face on the plane (c, n) bounded by the polygon; the polygon's corners
// are within `tolerance` of the plane, which its edges are given so OCCT
// accepts them. The face normal is n (the polygon runs counter-clockwise).
// With `topo`, the outline is made of its shared edges (`ids`: the corners'
// mesh vertices).
TopoDS_Face flat_face(const std::vector<Vec3>& p, const Vec3& c, const Vec3& n, double tolerance,
                      SharedTopology* topo = nullptr, const std::vector<int>& ids = {}) {
  TopoDS_Wire wire;
  if (topo != nullptr) {
    wire = topo->wire(ids);
    if (tolerance > 1e-7) raise_tolerance(wire, tolerance);
  } else {
    BRepBuilderAPI_MakePolygon polygon;
    for (const Vec3& q : p) polygon.Add(pnt(q));
    polygon.Close();
    if (!polygon.IsDone()) throw GeometryFailure("cannot build a panel outline (repeated corners)");
    wire = polygon.Wire();
    if (tolerance > 1e-7) ShapeFix_ShapeTolerance().SetTolerance(wire, tolerance);
  }
  const gp_Pln plane(pnt(c), gp_Dir(n.x(), n.y(), n.z()));
  BRepBuilderAPI_MakeFace face(plane, wire, Standard_True);
  if (!face.IsDone()) throw GeometryFailure("cannot build a flat panel face");
  return face.Face();
}

// The bilinear patch of a bent quad bounded by its shared edges: each edge
// gets its line on the patch (a side of the unit square, parameterized like
// the edge: 0 at its smaller vertex index, its length at the other).
TopoDS_Face shared_bilinear_face(const Handle(Geom_BezierSurface) & patch,
                                 const std::vector<int>& ids, SharedTopology& topo) {
  static const gp_Pnt2d corner[4] = {gp_Pnt2d(0, 0), gp_Pnt2d(1, 0), gp_Pnt2d(1, 1),
                                     gp_Pnt2d(0, 1)};
  BRep_Builder builder;
  TopoDS_Face face;
  builder.MakeFace(face, patch, 1e-7);
  TopoDS_Wire wire;
  builder.MakeWire(wire);
  for (int k = 0; k < 4; ++k) {
    const int a = ids[k], b = ids[(k + 1) % 4];
    const TopoDS_Edge edge = topo.edge(a, b);
    double first = 0, last = 0;
    BRep_Tool::Range(edge, first, last);
    TColgp_Array1OfPnt2d poles(1, 2);
    poles(1) = corner[a < b ? k : (k + 1) % 4];
    poles(2) = corner[a < b ? (k + 1) % 4 : k];
    TColStd_Array1OfReal knots(1, 2);
    knots(1) = first;
    knots(2) = last;
    TColStd_Array1OfInteger mults(1, 2);
    mults(1) = mults(2) = 2;
    builder.UpdateEdge(edge, new Geom2d_BSplineCurve(poles, knots, mults, 1), face,
                       BRep_Tool::Tolerance(edge));
    builder.Add(wire, edge);
  }
  wire.Closed(Standard_True);
  builder.Add(face, wire);
  return face;
}

// `pieces`: the corner lists of a panel modelled as flat pieces (empty: not).
// The faces of one panel (corner indices panel-local), see PanelFaceList.
struct PanelSpec {
  bool compound = false;
  struct Face {
    std::vector<int> corners;
    bool bilinear = false;
    Vec3 origin = Vec3::Zero(), normal = Vec3::Zero();
    double tolerance = 0.0;
  };
  std::vector<Face> faces;
};

PanelSpec describe_panel(const std::vector<Vec3>& p, const std::vector<Vec2>& uv,
                         const std::vector<std::vector<int>>& pieces, double planar_tolerance) {
  PanelSpec spec;
  auto flat = [&](std::vector<int> corners, const Vec3& c, const Vec3& n, double tolerance) {
    PanelSpec::Face f;
    f.corners = std::move(corners);
    f.origin = c;
    f.normal = n;
    f.tolerance = tolerance;
    spec.faces.push_back(std::move(f));
  };
  if (pieces.size() > 1) {
    // Modelled as flat pieces (a boundary panel bent along node diagonals):
    // one flat face per piece, the model every figure is measured on.
    spec.compound = true;
    for (const std::vector<int>& piece : pieces) {
      std::vector<Vec3> q;
      for (int i : piece) q.push_back(p[i]);
      Vec3 qc = Vec3::Zero();
      for (const Vec3& x : q) qc += x;
      qc /= double(q.size());
      const Vec3 qn = newell_normal(q);
      if (!(qn.norm() > 0)) continue;
      flat(piece, qc, qn.normalized(), off_plane(q, qc, qn.normalized()) * 1.01);
    }
    return spec;
  }
  std::vector<int> all(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) all[i] = static_cast<int>(i);
  // Planar within the tolerance: one flat face on the best plane through the
  // mean corner with Newell's normal (which follows the corner order).
  Vec3 c = Vec3::Zero();
  for (const Vec3& q : p) c += q;
  c /= double(p.size());
  const Vec3 newell = newell_normal(p);
  if (newell.norm() > 0) {
    const Vec3 n = newell.normalized();
    const double off = off_plane(p, c, n);
    if (off <= planar_tolerance) {
      flat(all, c, n, off * 1.01);
      return spec;
    }
  }
  if (p.size() == 4 && pieces.empty()) {
    // Bent quad: its bilinear patch, exact through the four corners.
    PanelSpec::Face f;
    f.corners = all;
    f.bilinear = true;
    spec.faces.push_back(f);
    return spec;
  }
  // Bent n-gon: the flat triangles of its (u,v) triangulation, in a compound.
  spec.compound = true;
  for (const auto& t : triangulate_polygon(uv)) {
    const std::vector<Vec3> tri = {p[t[0]], p[t[1]], p[t[2]]};
    const Vec3 n = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
    const double longest =
        std::max({(tri[1] - tri[0]).squaredNorm(), (tri[2] - tri[1]).squaredNorm(),
                  (tri[0] - tri[2]).squaredNorm()});
    // Collinear outline points give zero-area ears whose rounding-noise
    // normal could point anywhere: they add nothing to the panel, skip them.
    if (!(n.norm() > 1e-9 * longest)) continue;
    flat({t[0], t[1], t[2]}, (tri[0] + tri[1] + tri[2]) / 3.0, n.normalized(), 0.0);
  }
  return spec;
}

// The shape of a described panel. With `topo`, faces are bounded by shared
// edges (`ids`: the corners' mesh vertices); it throws
// SharedTopology::NotShareable for repeated corners.
TopoDS_Shape panel_shape(const std::vector<Vec3>& p, const PanelSpec& spec,
                         SharedTopology* topo = nullptr, const std::vector<int>& ids = {}) {
  BRep_Builder builder;
  TopoDS_Compound compound;
  if (spec.compound) builder.MakeCompound(compound);
  for (const PanelSpec::Face& f : spec.faces) {
    std::vector<Vec3> q;
    std::vector<int> q_ids;
    for (int i : f.corners) {
      q.push_back(p[static_cast<std::size_t>(i)]);
      if (topo != nullptr) q_ids.push_back(ids[static_cast<std::size_t>(i)]);
    }
    TopoDS_Face face;
    if (f.bilinear) {
      // With the poles in this order du x dv points along the counter-clockwise normal.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Warray-bounds"  // GCC 12 false positive in NCollection_Array2
      TColgp_Array2OfPnt poles(1, 2, 1, 2);
      poles(1, 1) = pnt(q[0]);
      poles(2, 1) = pnt(q[1]);
      poles(2, 2) = pnt(q[2]);
      poles(1, 2) = pnt(q[3]);
      Handle(Geom_BezierSurface) patch = new Geom_BezierSurface(poles);
#pragma GCC diagnostic pop
      if (topo != nullptr) {
        face = shared_bilinear_face(patch, q_ids, *topo);
      } else {
        BRepBuilderAPI_MakeFace bilinear(patch, 0.0, 1.0, 0.0, 1.0, 1e-7);
        if (!bilinear.IsDone()) throw GeometryFailure("cannot build a bilinear panel face");
        face = bilinear.Face();
      }
    } else {
      face = flat_face(q, f.origin, f.normal, f.tolerance, topo, q_ids);
    }
    if (!spec.compound) return face;
    builder.Add(compound, face);
  }
  return compound;
}

// Panel k of the mesh: its corners and their (u,v), and how it is modelled.
PanelSpec describe_panel(const PanelMesh& mesh, std::size_t k, double planar_tolerance,
                         std::vector<Vec3>& p) {
  p.clear();
  for (int v : mesh.panels[k]) p.push_back(mesh.xyz[v]);
  std::vector<std::vector<int>> pieces;
  if (modelled_as_pieces(mesh, k))
    pieces = split_polygon(static_cast<int>(p.size()), panel_bends(mesh, k));
  return describe_panel(p, panel_corner_uv(mesh, k), pieces, planar_tolerance);
}

}  // namespace

std::string panels_to_brep(const PanelMesh& mesh, double planar_tolerance) {
  require_in_range("planar_tolerance", planar_tolerance, 1e-7, 1e6);
  try {
    BRep_Builder builder;
    TopoDS_Compound all;
    builder.MakeCompound(all);
    SharedTopology topo(mesh);
    std::vector<Vec3> p;
    for (std::size_t k = 0; k < mesh.panels.size(); ++k) {
      report_progress(double(k) / double(mesh.panels.size()), "building panel faces");
      const PanelSpec spec = describe_panel(mesh, k, planar_tolerance, p);
      TopoDS_Shape shape;
      try {
        shape = panel_shape(p, spec, &topo, mesh.panels[k]);
      } catch (const SharedTopology::NotShareable&) {
        // Two corners at one point: a face of its own, as the outline allows.
        shape = panel_shape(p, spec);
      }
      builder.Add(all, shape);
    }
    return to_brep(all);
  } catch (const Standard_Failure& e) {
    throw GeometryFailure(std::string("building panel faces failed: ") + e.GetMessageString());
  }
}

PanelFaceList panel_faces(const PanelMesh& mesh, double planar_tolerance) {
  require_in_range("planar_tolerance", planar_tolerance, 1e-7, 1e6);
  PanelFaceList out;
  out.panel_offsets.push_back(0);
  out.corner_offsets.push_back(0);
  std::vector<Vec3> p;
  for (std::size_t k = 0; k < mesh.panels.size(); ++k) {
    const PanelSpec spec = describe_panel(mesh, k, planar_tolerance, p);
    out.compound.push_back(spec.compound ? 1 : 0);
    for (const PanelSpec::Face& f : spec.faces) {
      for (int i : f.corners) out.corners.push_back(mesh.panels[k][static_cast<std::size_t>(i)]);
      out.corner_offsets.push_back(static_cast<int>(out.corners.size()));
      out.bilinear.push_back(f.bilinear ? 1 : 0);
      out.origin.push_back(f.origin);
      out.normal.push_back(f.normal);
      out.tolerance.push_back(f.tolerance);
    }
    out.panel_offsets.push_back(static_cast<int>(out.bilinear.size()));
  }
  return out;
}

std::string rods_to_brep(const PanelMesh& mesh) {
  try {
    BRep_Builder builder;
    TopoDS_Compound all;
    builder.MakeCompound(all);
    // One vertex per node, shared by the rods meeting there.
    std::unordered_map<int, TopoDS_Vertex> vertex;
    auto node = [&](int v) -> const TopoDS_Vertex& {
      auto it = vertex.find(v);
      if (it == vertex.end()) {
        it = vertex.emplace(v, BRepBuilderAPI_MakeVertex(pnt(mesh.xyz[v])).Vertex()).first;
      }
      return it->second;
    };
    for (const auto& rod : mesh.rods) {
      builder.Add(all, BRepBuilderAPI_MakeEdge(node(rod[0]), node(rod[1])).Edge());
    }
    return to_brep(all);
  } catch (const Standard_Failure& e) {
    throw GeometryFailure(std::string("building rod edges failed: ") + e.GetMessageString());
  }
}

std::string nodes_to_brep(const PanelMesh& mesh) {
  BRep_Builder builder;
  TopoDS_Compound all;
  builder.MakeCompound(all);
  for (std::size_t v = 0; v < mesh.xyz.size(); ++v) {
    if (is_node(mesh, static_cast<int>(v))) {
      builder.Add(all, BRepBuilderAPI_MakeVertex(pnt(mesh.xyz[v])).Vertex());
    }
  }
  return to_brep(all);
}

}  // namespace tessella
