#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_Copy.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <cmath>

#include "faceset/face_set_impl.h"
#include "faceset/touching_faces.h"
#include "geometry/brep_string.h"
#include "tessella/errors.h"

namespace tessella {

FaceSet::FaceSet(std::shared_ptr<Impl> impl) : impl_(std::move(impl)) {}

std::size_t FaceSet::size() const { return impl_->faces.size(); }
std::shared_ptr<const SurfaceFace> FaceSet::face(std::size_t i) const { return impl_->faces.at(i); }
std::size_t FaceSet::shared_edge_count() const { return impl_->shared.size(); }

namespace {

// Faces closer than this along edges they do not share are sewn: 1e-5 of the
// shape's size (0.65 mm on a 65 m roof, 0.1 mm on a 10 m box) bridges the
// gaps of faces modelled apart or exported without sewing, and is far below
// any panel.
constexpr double kSewFraction = 1e-5;

}  // namespace

bool FaceSet::sewn() const { return impl_->sewn; }

FaceSet FaceSet::from_brep_string(const std::string& brep) {
  TopoDS_Shape shape = shape_from_brep_string(brep);
  TopTools_IndexedMapOfShape face_map;
  TopExp::MapShapes(shape, TopAbs_FACE, face_map);
  if (face_map.IsEmpty()) throw InvalidGeometry("the shape has no face: select faces");
  auto impl = std::make_shared<Impl>();
  if (face_map.Extent() > 1) {
    std::vector<TopoDS_Face> faces;
    for (int i = 1; i <= face_map.Extent(); ++i) faces.push_back(TopoDS::Face(face_map(i)));
    Bnd_Box box;
    BRepBndLib::Add(shape, box);
    const double tolerance = box.IsVoid() ? 0.0 : kSewFraction * std::sqrt(box.SquareExtent());
    if (tolerance > 0 && have_touching_free_edges(faces, tolerance)) {
      faces = sew_faces(faces, tolerance);
      TopoDS_Compound sewn;
      BRep_Builder builder;
      builder.MakeCompound(sewn);
      face_map.Clear();
      for (const TopoDS_Face& f : faces) builder.Add(sewn, f), face_map.Add(f);
      shape = sewn;
      impl->sewn = true;
    }
  }
  // Each face copied with its geometry (BRepBuilderAPI_Copy): faces built on
  // one surface would otherwise share it across threads. The copier maps
  // every edge to its copy, whose curve on the copied face is looked up.
  std::vector<std::unique_ptr<BRepBuilderAPI_Copy>> copies;
  for (int i = 1; i <= face_map.Extent(); ++i) {
    const TopoDS_Face& face = TopoDS::Face(face_map(i));
    impl->original.push_back(face);
    try {
      copies.push_back(std::make_unique<BRepBuilderAPI_Copy>(face, true));
      const TopoDS_Face copy = TopoDS::Face(copies.back()->Shape());
      impl->occt.push_back(copy);
      impl->faces.push_back(std::make_shared<SurfaceFace>(SurfaceFace::from_occt_face(copy)));
    } catch (const InvalidGeometry& e) {
      throw InvalidGeometry("face " + std::to_string(i) + ": " + e.what());
    } catch (const Standard_Failure& e) {
      throw InvalidGeometry("face " + std::to_string(i) +
                            ": cannot be copied: " + e.GetMessageString());
    }
  }
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  for (int e = 1; e <= edge_faces.Extent(); ++e) {
    const TopoDS_Edge& edge = TopoDS::Edge(edge_faces.FindKey(e));
    if (BRep_Tool::Degenerated(edge)) continue;
    std::vector<int> faces;
    for (TopTools_ListOfShape::Iterator it(edge_faces(e)); it.More(); it.Next()) {
      const int f = face_map.FindIndex(it.Value()) - 1;
      if (f >= 0 && std::find(faces.begin(), faces.end(), f) == faces.end()) faces.push_back(f);
    }
    // A seam (one face on both sides) is the face's own business; an edge of
    // three or more faces (non-manifold) is left as a free trim of each.
    if (faces.size() != 2) continue;
    std::sort(faces.begin(), faces.end());
    SharedEdge s;
    s.faces = {faces[0], faces[1]};
    bool ok = true;
    for (int side = 0; side < 2; ++side) {
      const int f = faces[static_cast<std::size_t>(side)];
      const TopTools_ListOfShape& copied = copies[static_cast<std::size_t>(f)]->Modified(edge);
      if (copied.IsEmpty()) {
        ok = false;
        break;
      }
      double first = 0, last = 0;
      s.pcurve[static_cast<std::size_t>(side)] = BRep_Tool::CurveOnSurface(
          TopoDS::Edge(copied.First()), impl->occt[static_cast<std::size_t>(f)], first, last);
      if (s.pcurve[static_cast<std::size_t>(side)].IsNull()) ok = false;
      if (side == 0) s.first = first, s.last = last;
    }
    if (!ok) continue;
    TopoDS_Vertex v0, v1;
    TopExp::Vertices(edge, v0, v1);
    s.closed = !v0.IsNull() && v0.IsSame(v1);
    BRepBndLib::Add(edge, s.box, false);  // the curve, enlarged by the edge's tolerance
    impl->shared.push_back(s);
  }
  return FaceSet(std::move(impl));
}

}  // namespace tessella
