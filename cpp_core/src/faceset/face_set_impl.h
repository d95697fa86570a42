// What a FaceSet holds (tessella/face_set.h): the faces, each with its own
// copy of the geometry, and the edges two faces share with their curves on
// each face.
#pragma once

#include <Bnd_Box.hxx>
#include <Geom2d_Curve.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <array>
#include <memory>
#include <mutex>
#include <vector>

#include "faceset/surface_groups.h"
#include "tessella/face_set.h"
#include "tessella/surface_face.h"

namespace tessella {

// An edge between faces a < b: its curve on each face (the parameter is the
// edge's own on both, as in every valid B-rep: SameParameter).
struct SharedEdge {
  std::array<int, 2> faces{};
  std::array<Handle(Geom2d_Curve), 2> pcurve;
  double first = 0, last = 0;
  // The edge's two vertices lie at its ends (a closed edge: the same point).
  bool closed = false;
  // The edge's 3D box, grown by its tolerance: its curve on either face lies
  // inside (a mesh vertex outside, by more than a match tolerance, is not on it).
  Bnd_Box box;
};

struct FaceSet::Impl {
  std::vector<TopoDS_Face> occt;  // the copies the SurfaceFaces were built from
  std::vector<std::shared_ptr<const SurfaceFace>> faces;
  std::vector<SharedEdge> shared;
  // The diagonal of the shape's B-rep box (OCCT's, as FreeCAD's BoundBox):
  // the set's model size.
  double model_size = 0;
  std::size_t given_count = 0;
  std::vector<int> given_index;  // per face, its index in the shape as given
  std::vector<FaceSet::Skipped> skipped;
  bool sewn = false;  // faces touching along edges they did not share were sewn
  // The faces as given (sewn), sharing their edges: what surface_groups unifies.
  std::vector<TopoDS_Face> original;
  mutable std::once_flag groups_once;
  mutable std::vector<SurfaceGroup> groups;
};

}  // namespace tessella
