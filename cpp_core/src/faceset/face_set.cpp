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
#include <cstdio>

#include "faceset/face_set_impl.h"
#include "faceset/touching_faces.h"
#include "geometry/brep_string.h"
#include "tessella/errors.h"

namespace tessella {

FaceSet::FaceSet(std::shared_ptr<Impl> impl) : impl_(std::move(impl)) {}

std::size_t FaceSet::size() const { return impl_->faces.size(); }
std::shared_ptr<const SurfaceFace> FaceSet::face(std::size_t i) const { return impl_->faces.at(i); }
std::size_t FaceSet::shared_edge_count() const { return impl_->shared.size(); }
std::size_t FaceSet::given_count() const { return impl_->given_count; }
int FaceSet::given_index(std::size_t i) const { return impl_->given_index.at(i); }
const std::vector<FaceSet::Skipped>& FaceSet::skipped() const { return impl_->skipped; }

namespace {

// Faces closer than this along edges they do not share are sewn: 1e-5 of the
// shape's size (0.65 mm on a 65 m roof, 0.1 mm on a 10 m box) bridges the
// gaps of faces modelled apart or exported without sewing, and is far below
// any panel.
constexpr double kSewFraction = 1e-5;

}  // namespace

bool FaceSet::sewn() const { return impl_->sewn; }

namespace {

// The diagonal of the face's tight box (its trimmed surface, not its poles').
double tight_extent(const TopoDS_Face& face) {
  Bnd_Box box;
  BRepBndLib::AddOptimal(face, box, false, false);
  return box.IsVoid() ? 0.0 : std::sqrt(box.SquareExtent());
}

// The faces, sewn where they touch along edges they do not share, each
// copied with its geometry (BRepBuilderAPI_Copy): faces built on one surface
// would otherwise share it across threads. The copier maps every edge to
// its copy, whose curve on the copied face is looked up. `shape` and
// `face_map` become the faces' compound where they were sewn or some left
// out (else the shape's own edge order stays). A face without area is
// recorded in `without_area` (its index in `faces`) when `skip` is
// set, else refused.
std::vector<std::unique_ptr<BRepBuilderAPI_Copy>> build_faces(
    std::vector<TopoDS_Face> faces, const std::vector<int>& given, double tolerance, bool skip,
    FaceSet::Impl& impl, TopoDS_Shape& shape, TopTools_IndexedMapOfShape& face_map,
    std::vector<FaceSet::Skipped>& without_area) {
  const bool sew = faces.size() > 1 && tolerance > 0 && have_touching_free_edges(faces, tolerance);
  if (sew) {
    faces = sew_faces(faces, tolerance);
    impl.sewn = true;
  }
  if (sew || face_map.Extent() != static_cast<int>(faces.size())) {
    // The shape is now these faces (sewn, or some left out).
    TopoDS_Compound compound;
    BRep_Builder builder;
    builder.MakeCompound(compound);
    face_map.Clear();
    for (const TopoDS_Face& f : faces) builder.Add(compound, f), face_map.Add(f);
    shape = compound;
  }
  std::vector<std::unique_ptr<BRepBuilderAPI_Copy>> copies;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const std::string name = "face " + std::to_string(given[i] + 1) + ": ";
    try {
      copies.push_back(std::make_unique<BRepBuilderAPI_Copy>(faces[i], true));
      const TopoDS_Face copy = TopoDS::Face(copies.back()->Shape());
      auto face = std::make_shared<SurfaceFace>(SurfaceFace::from_occt_face(copy));
      // A sliver narrower than the sewing tolerance (its area over its
      // extent bounds its width) is a slit as far as the set goes: its two
      // sides are within the tolerance of each other. The extent is the
      // face's own, tight: a trimmed B-spline face's box (model_size) may be
      // its whole surface's, and a triangle of 12 to 16 mm cut out of a 10 m
      // surface by three planes read as 0.01 mm wide and was left out, its
      // neighbours' panels leaving a hole there
      // (bench_faces.random_face_set(430)).
      if (skip && face->area() < tolerance * face->model_size()) {
        const double extent = tight_extent(copy);
        if (face->area() < tolerance * extent) {
          char width[64];
          std::snprintf(width, sizeof width, "%.3g", face->area() / extent);
          throw FaceWithoutArea(std::string("the face is a sliver about ") + width +
                                " mm wide, narrower than the set's sewing tolerance");
        }
      }
      impl.original.push_back(faces[i]);
      impl.occt.push_back(copy);
      impl.faces.push_back(std::move(face));
    } catch (const FaceWithoutArea& e) {
      if (!skip) throw FaceWithoutArea(name + e.what());
      without_area.push_back({static_cast<int>(i), e.what()});
    } catch (const InvalidGeometry& e) {
      throw InvalidGeometry(name + e.what());
    } catch (const Standard_Failure& e) {
      throw InvalidGeometry(name + "cannot be copied: " + e.GetMessageString());
    }
  }
  return copies;
}

}  // namespace

FaceSet FaceSet::from_brep_string(const std::string& brep) {
  TopoDS_Shape shape = shape_from_brep_string(brep);
  TopTools_IndexedMapOfShape face_map;
  TopExp::MapShapes(shape, TopAbs_FACE, face_map);
  if (face_map.IsEmpty()) throw InvalidGeometry("the shape has no face: select faces");
  std::vector<TopoDS_Face> faces;
  std::vector<int> given;
  for (int i = 1; i <= face_map.Extent(); ++i)
    faces.push_back(TopoDS::Face(face_map(i))), given.push_back(i - 1);
  Bnd_Box box;
  BRepBndLib::Add(shape, box);
  const double tolerance = box.IsVoid() ? 0.0 : kSewFraction * std::sqrt(box.SquareExtent());
  auto impl = std::make_shared<Impl>();
  impl->model_size = box.IsVoid() ? 0.0 : std::sqrt(box.SquareExtent());
  impl->given_count = faces.size();
  const bool skip = faces.size() > 1;
  std::vector<Skipped> without_area;
  auto copies = build_faces(faces, given, tolerance, skip, *impl, shape, face_map, without_area);
  if (!without_area.empty()) {
    // Left out, the slit's two neighbours touch along edges they shared
    // with it: built again, without it, they are sewn to each other.
    std::vector<TopoDS_Face> kept;
    std::vector<int> kept_given;
    std::size_t next = 0;
    for (std::size_t i = 0; i < faces.size(); ++i) {
      if (next < without_area.size() && without_area[next].face == static_cast<int>(i)) {
        impl->skipped.push_back({given[i], without_area[next].why});
        ++next;
        continue;
      }
      kept.push_back(faces[i]), kept_given.push_back(given[i]);
    }
    if (kept.empty())
      throw FaceWithoutArea("no face of the shape encloses an area (" + impl->skipped[0].why + ")");
    Impl& again = *impl;
    again.occt.clear(), again.faces.clear(), again.original.clear(), again.sewn = false;
    without_area.clear();
    given = kept_given;
    copies = build_faces(kept, given, tolerance, false, again, shape, face_map, without_area);
  }
  impl->given_index = given;
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
