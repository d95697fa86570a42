// Faces of a set that lie on one surface: split from it (seed 004's roof in
// four sub-surfaces, a façade cut into zones) and joined along shared edges.
// A method that traces curves (boundary_driven) traces them on their union,
// so they run on across the edges between the faces.
#pragma once

#include <memory>
#include <vector>

#include "tessella/face_set.h"
#include "tessella/surface_face.h"

namespace tessella {

struct SurfaceGroup {
  std::vector<int> members;                 // set indices, increasing
  std::shared_ptr<const SurfaceFace> face;  // their union, on the same (u,v)
};

// The groups of two or more faces (OCCT's ShapeUpgrade_UnifySameDomain says
// which faces lie on one surface and makes their union); a group whose faces
// do not share the union's (u,v) (the same plane parameterized apart) is
// left out. Computed once per set, on first use.
const std::vector<SurfaceGroup>& surface_groups(const FaceSet& set);

}  // namespace tessella
