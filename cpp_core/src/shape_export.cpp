#include "tessella/shape_export.h"

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GeomLProp_SLProps.hxx>
#include <Geom_BezierSurface.hxx>
#include <Geom_Surface.hxx>
#include <ShapeFix_ShapeTolerance.hxx>
#include <Standard_Failure.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Face.hxx>
#include <sstream>

#include "tessella/errors.h"
#include "tessella/panel_model.h"
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

// Makes the face's normal agree with the corner order (counter-clockwise).
TopoDS_Face oriented(TopoDS_Face face, const Vec3& wanted) {
  Handle(Geom_Surface) s = BRep_Tool::Surface(face);
  double u0, u1, v0, v1;
  s->Bounds(u0, u1, v0, v1);
  const double u = std::isfinite(u0) && std::isfinite(u1) ? 0.5 * (u0 + u1) : 0.0;
  const double v = std::isfinite(v0) && std::isfinite(v1) ? 0.5 * (v0 + v1) : 0.0;
  GeomLProp_SLProps props(s, u, v, 1, 1e-9);
  if (!props.IsNormalDefined()) return face;
  gp_Dir n = props.Normal();
  if (face.Orientation() == TopAbs_REVERSED) n.Reverse();
  if (n.X() * wanted.x() + n.Y() * wanted.y() + n.Z() * wanted.z() < 0) face.Reverse();
  return face;
}

TopoDS_Shape panel_shape(const std::vector<Vec3>& p, const std::vector<Vec2>& uv,
                         double planar_tolerance) {
  BRepBuilderAPI_MakePolygon polygon;
  for (const Vec3& q : p) polygon.Add(pnt(q));
  polygon.Close();
  if (!polygon.IsDone()) throw GeometryFailure("cannot build a panel outline (repeated corners)");
  TopoDS_Wire wire = polygon.Wire();
  // A wire whose edges carry the planar tolerance lets OCCT accept a plane
  // that misses the corners by at most that much.
  ShapeFix_ShapeTolerance().SetTolerance(wire, planar_tolerance);
  const Vec3 normal = newell_normal(p);
  BRepBuilderAPI_MakeFace planar(wire, Standard_True);
  if (planar.IsDone()) return oriented(planar.Face(), normal);
  if (p.size() == 4) {
    // Bent quad: its bilinear patch, exact through the four corners.
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
    if (bilinear.IsDone()) return oriented(bilinear.Face(), normal);
  }
  // Bent n-gon: the flat triangles of its (u,v) triangulation, in a compound.
  BRep_Builder builder;
  TopoDS_Compound fan;
  builder.MakeCompound(fan);
  for (const auto& t : triangulate_polygon(uv)) {
    const Vec3 &a = p[t[0]], &b = p[t[1]], &c = p[t[2]];
    BRepBuilderAPI_MakePolygon tri(pnt(a), pnt(b), pnt(c), Standard_True);
    if (!tri.IsDone()) continue;
    BRepBuilderAPI_MakeFace f(tri.Wire(), Standard_True);
    if (f.IsDone()) builder.Add(fan, oriented(f.Face(), (b - a).cross(c - a)));
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
      builder.Add(all, panel_shape(p, panel_corner_uv(mesh, k), planar_tolerance));
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
    for (const auto& rod : mesh.rods) {
      builder.Add(all,
                  BRepBuilderAPI_MakeEdge(pnt(mesh.xyz[rod[0]]), pnt(mesh.xyz[rod[1]])).Edge());
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
