#include "faceset/surface_groups.h"

#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_Copy.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <Geom_Surface.hxx>
#include <ShapeAnalysis_FreeBounds.hxx>
#include <ShapeFix_Face.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Wire.hxx>
#include <limits>
#include <map>
#include <vector>

#include "faceset/face_set_impl.h"
#include "geometry/segment_closest.h"
#include "geometry/trim_deflection.h"
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

// The union of `faces` (on one surface, sharing their common edges) made
// from their free boundary: their own edges and pcurves, the largest wire
// outside, the others holes. Null if it cannot be made.
TopoDS_Face union_of_free_boundary(const std::vector<TopoDS_Face>& faces) {
  TopoDS_Compound all;
  BRep_Builder builder;
  builder.MakeCompound(all);
  for (const TopoDS_Face& f : faces) builder.Add(all, f);
  ShapeAnalysis_FreeBounds bounds(all, Standard_False, Standard_False);
  for (TopExp_Explorer w(bounds.GetOpenWires(), TopAbs_WIRE); w.More(); w.Next()) return {};
  std::vector<TopoDS_Wire> wires;
  std::vector<double> extent;
  for (TopExp_Explorer w(bounds.GetClosedWires(), TopAbs_WIRE); w.More(); w.Next()) {
    Bnd_Box box;
    BRepBndLib::Add(w.Current(), box);
    wires.push_back(TopoDS::Wire(w.Current()));
    extent.push_back(box.IsVoid() ? 0.0 : box.SquareExtent());
  }
  if (wires.empty()) return {};
  std::size_t outer = 0;
  for (std::size_t i = 1; i < wires.size(); ++i)
    if (extent[i] > extent[outer]) outer = i;
  BRepBuilderAPI_MakeFace make(BRep_Tool::Surface(faces[0]), wires[outer], Standard_True);
  if (!make.IsDone()) return {};
  for (std::size_t i = 0; i < wires.size(); ++i)
    if (i != outer) make.Add(wires[i]);
  ShapeFix_Face fix(make.Face());
  fix.Perform();
  const TopoDS_Face made = fix.Face();
  if (made.IsNull() || !BRepCheck_Analyzer(made).IsValid()) return {};
  return made;
}

// Whether every point of `whole`'s trim polylines lies on a trim of one of
// `members` (in 3D, within a few trim deflections): a union whose pcurves
// were approximated (OCCT's UnifySameDomain concatenating the arcs of a
// hole cut in four) can put its trim a metre off, and the faces' layout
// traced on it then leaves holes and walks lines for a face that is not
// there.
bool same_trims(const std::vector<const SurfaceFace*>& members, const SurfaceFace& whole) {
  const double deflection = trim_deflection(whole, 0.0);
  const double tol = 4 * deflection + 1e-7 * whole.model_size();
  std::vector<std::vector<Vec3>> lines;
  for (const SurfaceFace* m : members)
    for (const TrimLoop& loop : m->trim_loops(deflection)) lines.push_back(loop.xyz);
  for (const TrimLoop& loop : whole.trim_loops(deflection))
    for (const Vec3& p : loop.xyz) {
      double best = std::numeric_limits<double>::infinity();
      for (const std::vector<Vec3>& line : lines)
        for (std::size_t i = 0; i < line.size() && best > tol; ++i) {
          const Vec3 a = line[i], d = line[(i + 1) % line.size()] - a;
          best = std::min(best, (a + closest_fraction(a, d, p) * d - p).norm());
        }
      if (best > tol) return false;
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
      std::vector<TopoDS_Face> originals;
      std::vector<const SurfaceFace*> member_faces;
      for (int f : faces) {
        originals.push_back(set.original[static_cast<std::size_t>(f)]);
        member_faces.push_back(set.faces[static_cast<std::size_t>(f)].get());
      }
      // The union from the faces' own free boundary first, UnifySameDomain's
      // (which may approximate the edges it merges) if that cannot be made;
      // either only if its trims are the faces'.
      for (const TopoDS_Face& candidate :
           {union_of_free_boundary(originals), TopoDS::Face(unions(index))}) {
        if (candidate.IsNull()) continue;
        BRepBuilderAPI_Copy copy(candidate, true);
        std::shared_ptr<SurfaceFace> face;
        try {
          face = std::make_shared<SurfaceFace>(
              SurfaceFace::from_occt_face(TopoDS::Face(copy.Shape())));
        } catch (const std::exception&) {
          continue;
        }
        bool same = true;
        for (int f : faces) same = same && same_parameterization(*set.faces[f], *face);
        if (!same || !same_trims(member_faces, *face)) continue;
        out.push_back({faces, face});
        break;
      }
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
