#include "faceset/touching_faces.h"

#include <BRepAdaptor_Curve.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <array>

#include "tessella/errors.h"

namespace tessella {

namespace {

// A free edge's ends and middle, and the face it bounds.
struct FreeEdge {
  std::size_t face;
  std::array<gp_Pnt, 3> at;  // start, middle, end
};

TopoDS_Compound compound_of(const std::vector<TopoDS_Face>& faces) {
  TopoDS_Compound c;
  BRep_Builder b;
  b.MakeCompound(c);
  for (const TopoDS_Face& f : faces) b.Add(c, f);
  return c;
}

}  // namespace

bool have_touching_free_edges(const std::vector<TopoDS_Face>& faces, double tolerance) {
  // How many faces each edge bounds (a seam counts its face once).
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndAncestors(compound_of(faces), TopAbs_EDGE, TopAbs_FACE, edge_faces);
  std::vector<FreeEdge> free;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (TopExp_Explorer ex(faces[f], TopAbs_EDGE); ex.More(); ex.Next()) {
      const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
      if (BRep_Tool::Degenerated(e) || BRep_Tool::IsClosed(e, faces[f])) continue;
      const int k = edge_faces.FindIndex(e);
      if (k == 0) continue;
      int owners = 0;
      for (TopTools_ListOfShape::Iterator it(edge_faces(k)); it.More(); it.Next())
        owners += it.Value().IsSame(faces[f]) ? 0 : 1;
      if (owners > 0) continue;  // shared already
      try {
        const BRepAdaptor_Curve c(e);
        const double a = c.FirstParameter(), b = c.LastParameter();
        free.push_back({f, {c.Value(a), c.Value(0.5 * (a + b)), c.Value(b)}});
      } catch (const Standard_Failure&) {
        // An edge without a 3D curve cannot be matched; sewing would fail on it too.
      }
    }
  }
  for (std::size_t i = 0; i < free.size(); ++i)
    for (std::size_t j = i + 1; j < free.size(); ++j) {
      if (free[i].face == free[j].face) continue;
      const auto& p = free[i].at;
      const auto& q = free[j].at;
      if (p[1].Distance(q[1]) > tolerance) continue;
      const bool same = p[0].Distance(q[0]) <= tolerance && p[2].Distance(q[2]) <= tolerance;
      const bool reversed = p[0].Distance(q[2]) <= tolerance && p[2].Distance(q[0]) <= tolerance;
      if (same || reversed) return true;
    }
  return false;
}

std::vector<TopoDS_Face> sew_faces(const std::vector<TopoDS_Face>& faces, double tolerance) {
  // No non-manifold sewing: an edge of three faces stays a free trim of each
  // (as in a face set read whole).
  BRepBuilderAPI_Sewing sewing(tolerance, true, true, true, false);
  for (const TopoDS_Face& f : faces) sewing.Add(f);
  try {
    sewing.Perform();
  } catch (const Standard_Failure& e) {
    throw InvalidGeometry(std::string("the faces touch along edges they do not share, and sewing "
                                      "them failed: ") +
                          e.GetMessageString());
  }
  std::vector<TopoDS_Face> out;
  out.reserve(faces.size());
  for (const TopoDS_Face& f : faces) {
    if (!sewing.IsModified(f)) {
      out.push_back(f);
      continue;
    }
    const TopoDS_Shape& m = sewing.Modified(f);
    if (m.IsNull() || m.ShapeType() != TopAbs_FACE)
      throw InvalidGeometry(
          "the faces touch along edges they do not share, and sewing them did "
          "not keep each face whole");
    out.push_back(TopoDS::Face(m));
  }
  return out;
}

}  // namespace tessella
