#include "tessella/shape_export.h"

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <Geom_BezierSurface.hxx>
#include <ShapeFix_ShapeTolerance.hxx>
#include <Standard_Failure.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Face.hxx>
#include <algorithm>
#include <gp_Pln.hxx>
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

// A flat face on the plane (c, n) bounded by the polygon; the polygon's corners
// are within `tolerance` of the plane, which its edges are given so OCCT
// accepts them. The face normal is n (the polygon runs counter-clockwise).
TopoDS_Face flat_face(const std::vector<Vec3>& p, const Vec3& c, const Vec3& n, double tolerance) {
  BRepBuilderAPI_MakePolygon polygon;
  for (const Vec3& q : p) polygon.Add(pnt(q));
  polygon.Close();
  if (!polygon.IsDone()) throw GeometryFailure("cannot build a panel outline (repeated corners)");
  TopoDS_Wire wire = polygon.Wire();
  if (tolerance > 1e-7) ShapeFix_ShapeTolerance().SetTolerance(wire, tolerance);
  const gp_Pln plane(pnt(c), gp_Dir(n.x(), n.y(), n.z()));
  BRepBuilderAPI_MakeFace face(plane, wire, Standard_True);
  if (!face.IsDone()) throw GeometryFailure("cannot build a flat panel face");
  return face.Face();
}

// `pieces`: the corner lists of a panel modelled as flat pieces (empty: not).
TopoDS_Shape panel_shape(const std::vector<Vec3>& p, const std::vector<Vec2>& uv,
                         const std::vector<std::vector<int>>& pieces, double planar_tolerance) {
  if (pieces.size() > 1) {
    // Modelled as flat pieces (a boundary panel bent along node diagonals):
    // one flat face per piece, the model every figure is measured on.
    BRep_Builder builder;
    TopoDS_Compound sheet;
    builder.MakeCompound(sheet);
    for (const std::vector<int>& piece : pieces) {
      std::vector<Vec3> q;
      for (int i : piece) q.push_back(p[i]);
      Vec3 qc = Vec3::Zero();
      for (const Vec3& x : q) qc += x;
      qc /= double(q.size());
      const Vec3 qn = newell_normal(q);
      if (!(qn.norm() > 0)) continue;
      builder.Add(sheet, flat_face(q, qc, qn.normalized(), off_plane(q, qc, qn.normalized()) * 1.01));
    }
    return sheet;
  }
  // Planar within the tolerance: one flat face on the best plane through the
  // mean corner with Newell's normal (which follows the corner order).
  Vec3 c = Vec3::Zero();
  for (const Vec3& q : p) c += q;
  c /= double(p.size());
  const Vec3 newell = newell_normal(p);
  if (newell.norm() > 0) {
    const Vec3 n = newell.normalized();
    const double off = off_plane(p, c, n);
    if (off <= planar_tolerance) return flat_face(p, c, n, off * 1.01);
  }
  if (p.size() == 4 && pieces.empty()) {
    // Bent quad: its bilinear patch, exact through the four corners; with the
    // poles in this order du x dv points along the counter-clockwise normal.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Warray-bounds"  // GCC 12 false positive in NCollection_Array2
    TColgp_Array2OfPnt poles(1, 2, 1, 2);
    poles(1, 1) = pnt(p[0]);
    poles(2, 1) = pnt(p[1]);
    poles(2, 2) = pnt(p[2]);
    poles(1, 2) = pnt(p[3]);
    Handle(Geom_BezierSurface) patch = new Geom_BezierSurface(poles);
#pragma GCC diagnostic pop
    BRepBuilderAPI_MakeFace bilinear(patch, 0.0, 1.0, 0.0, 1.0, 1e-7);
    if (bilinear.IsDone()) return bilinear.Face();
  }
  // Bent n-gon: the flat triangles of its (u,v) triangulation, in a compound.
  BRep_Builder builder;
  TopoDS_Compound fan;
  builder.MakeCompound(fan);
  for (const auto& t : triangulate_polygon(uv)) {
    const std::vector<Vec3> tri = {p[t[0]], p[t[1]], p[t[2]]};
    const Vec3 n = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
    const double longest =
        std::max({(tri[1] - tri[0]).squaredNorm(), (tri[2] - tri[1]).squaredNorm(),
                  (tri[0] - tri[2]).squaredNorm()});
    // Collinear outline points give zero-area ears whose rounding-noise
    // normal could point anywhere: they add nothing to the panel, skip them.
    if (!(n.norm() > 1e-9 * longest)) continue;
    builder.Add(fan, flat_face(tri, (tri[0] + tri[1] + tri[2]) / 3.0, n.normalized(), 0.0));
  }
  return fan;
}

}  // namespace

std::string panels_to_brep(const PanelMesh& mesh, double planar_tolerance) {
  require_in_range("planar_tolerance", planar_tolerance, 1e-7, 1e6);
  try {
    BRep_Builder builder;
    TopoDS_Compound all;
    builder.MakeCompound(all);
    for (std::size_t k = 0; k < mesh.panels.size(); ++k) {
      report_progress(double(k) / double(mesh.panels.size()), "building panel faces");
      std::vector<Vec3> p;
      for (int v : mesh.panels[k]) p.push_back(mesh.xyz[v]);
      std::vector<std::vector<int>> pieces;
      if (modelled_as_pieces(mesh, k))
        pieces = split_polygon(static_cast<int>(p.size()), panel_bends(mesh, k));
      builder.Add(all, panel_shape(p, panel_corner_uv(mesh, k), pieces, planar_tolerance));
    }
    return to_brep(all);
  } catch (const Standard_Failure& e) {
    throw GeometryFailure(std::string("building panel faces failed: ") + e.GetMessageString());
  }
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
