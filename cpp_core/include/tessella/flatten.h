// Flattening a curved panel: the surface patch inside the panel's (u,v)
// outline, meshed finely and flattened by least-squares conformal maps
// (LSCM), scaled to its 3D area; reports the flattening strain.
#pragma once

#include <vector>

#include "tessella/vec.h"

namespace tessella {

class SurfaceFace;
class FaceSet;
struct PanelMesh;

struct FlattenParams {
  int subdivisions = 8;  // each triangle of the (u,v) outline split into n^2 pieces
};

struct FlatPatch {
  // Boundary in the panel's corner order, counter-clockwise seen from the
  // front: `subdivisions` points per panel edge (corner first).
  std::vector<Vec2> outline;
  std::vector<int> corner_index;  // outline index of panel corner i
  double strain_max = 0.0;        // max |flat length / 3D length - 1| over mesh edges
  double strain_mean = 0.0;
  double area_3d = 0.0;  // area of the fine 3D mesh of the patch
  // Unit direction, in the flat frame, of the surface's u parameter (orientation mark).
  Vec2 u_direction{1.0, 0.0};
};

// Flattens the patch of `face` bounded by the (u,v) polygon `corner_uv` (a panel).
FlatPatch flatten_patch(const SurfaceFace& face, const std::vector<Vec2>& corner_uv,
                        const FlattenParams& params = {});

// flatten_patch for every panel of the mesh (panel order).
std::vector<FlatPatch> flatten_panels(const SurfaceFace& face, const PanelMesh& mesh,
                                      const FlattenParams& params = {});

// The panels of a face set's combined mesh, each on its own face
// (panel_face[p], an index into `set`; the mesh's corner_uv are on that face).
std::vector<FlatPatch> flatten_face_set_panels(const FaceSet& set, const PanelMesh& mesh,
                                               const std::vector<int>& panel_face,
                                               const FlattenParams& params = {});

}  // namespace tessella
