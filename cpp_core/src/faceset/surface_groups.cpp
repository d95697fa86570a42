#include "faceset/surface_groups.h"

#include <BRepBuilderAPI_Copy.hxx>
#include <BRep_Builder.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <Standard_Failure.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <map>

#include "faceset/face_set_impl.h"
#include "tessella/errors.h"

namespace tessella {

namespace {

// Whether `member` and `whole` give the same point at the same (u,v) (a 5 x 5
// grid over the member's bounds), within 1e-7 of the member's size.
bool same_parameterization(const SurfaceFace& member, const SurfaceFace& whole) {
  const UvBounds b = member.bounds();
  const double tol = 1e-7 * member.model_size();
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; j <= 4; ++j) {
      const double u = b.u_min + (b.u_max - b.u_min) * i / 4.0;
      const double v = b.v_min + (b.v_max - b.v_min) * j / 4.0;
      if ((member.point(u, v) - whole.point(u, v)).norm() > tol) return false;
    }
  return true;
}

std::vector<SurfaceGroup> find_groups(const FaceSet::Impl& set) {
  std::vector<SurfaceGroup> out;
  const std::size_t n = set.original.size();
  if (n < 2 || set.faces.size() != n) return out;
  TopoDS_Compound all;
  BRep_Builder builder;
  builder.MakeCompound(all);
  for (const TopoDS_Face& f : set.original) builder.Add(all, f);
  try {
    ShapeUpgrade_UnifySameDomain unify(all, true, true, false);
    unify.Build();
    TopTools_IndexedMapOfShape unions;
    std::map<int, std::vector<int>> members;  // union index -> set faces
    for (std::size_t f = 0; f < n; ++f) {
      const TopTools_ListOfShape& made = unify.History()->Modified(set.original[f]);
      if (made.Extent() != 1 || made.First().ShapeType() != TopAbs_FACE) continue;
      members[unions.Add(made.First())].push_back(static_cast<int>(f));
    }
    for (const auto& [index, faces] : members) {
      if (faces.size() < 2) continue;
      BRepBuilderAPI_Copy copy(TopoDS::Face(unions(index)), true);
      auto face =
          std::make_shared<SurfaceFace>(SurfaceFace::from_occt_face(TopoDS::Face(copy.Shape())));
      bool same = true;
      for (int f : faces) same = same && same_parameterization(*set.faces[f], *face);
      if (same) out.push_back({faces, face});
    }
  } catch (const Standard_Failure&) {
    return {};
  } catch (const std::exception&) {  // a group only lets curves run on: without it each face alone
    return {};
  }
  return out;
}

}  // namespace

const std::vector<SurfaceGroup>& surface_groups(const FaceSet& set) {
  const FaceSet::Impl& impl = set.impl();
  std::call_once(impl.groups_once, [&impl] { impl.groups = find_groups(impl); });
  return impl.groups;
}

}  // namespace tessella
