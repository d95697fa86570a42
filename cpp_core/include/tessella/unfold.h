// Unfolding: every panel drawn flat with its true edge lengths.
//
// A panel is cut into triangles (a quad about the diagonal with the smaller
// fold, an n-gon by the triangulation of its (u,v) outline) and the triangles
// are laid out flat one after the other across their shared diagonals, so every
// edge and every diagonal keeps its 3D length exactly. A shared diagonal whose
// two triangles meet at more than `fold_tolerance_deg` is a fold: a bent quad
// becomes two flat triangles folded along that diagonal (seed 000, 6.1.2).
#pragma once

#include <array>
#include <vector>

#include "tessella/panel_mesh.h"
#include "tessella/vec.h"

namespace tessella {

struct UnfoldParams {
  // Folds under this angle (degrees) count as flat (no fold line). 0.5 deg: a
  // sheet takes a smaller kink when it is fixed (a press brake does not form
  // less), and 92-96% of the real folds of the grids, the walking agent and
  // boundary_driven on the bundled and the test faces are larger
  // (bench/buildable_boundaries.py, docs/fabrication.md).
  double fold_tolerance_deg = 0.5;
};

struct Fold {
  int a = -1, b = -1;  // corner indices (panel-local) of the fold line, a < b
  // Degrees between the two triangles' planes: 0 = flat. Positive for a
  // valley seen from the panel's front (the side its normal points to).
  double angle_deg = 0.0;
};

struct FlatPanel {
  // Corners in the panel's order, counter-clockwise, seen from the front.
  // Corner 0 at the origin, edge 0->1 along +x.
  std::vector<Vec2> outline;
  std::vector<Fold> folds;  // empty for a flat panel
  // The triangles (corner indices, the panel's orientation) it was unfolded by.
  std::vector<std::array<int, 3>> triangles;
  // The outline crosses itself (a strongly bent n-gon unfolded edge by edge):
  // not cuttable as drawn; flatten it as a curved patch instead.
  bool self_intersecting = false;
  // Largest |fold angle| among all diagonals, also those under the tolerance.
  double max_fold_deg = 0.0;
  // Unit direction, in the flat frame, of the surface's u parameter across the
  // panel (least-squares fit of the corners): the orientation mark.
  Vec2 u_direction{1.0, 0.0};
};

// Unfolds one panel from its 3D corners and their (u,v) (same order).
FlatPanel unfold_panel(const std::vector<Vec3>& xyz, const std::vector<Vec2>& uv,
                       const UnfoldParams& params = {});

// Unfolds a panel cut into the given triangles (corner triples in the panel's
// orientation, forming a tree across shared diagonals).
FlatPanel unfold_triangles(const std::vector<Vec3>& xyz, const std::vector<Vec2>& uv,
                           const std::vector<std::array<int, 3>>& triangles,
                           const UnfoldParams& params = {});

// Unfolds every panel of the mesh (a panel modelled as flat pieces by its
// pieces, see mesh/boundary_pieces.h: only its bend lines fold), in panel order.
std::vector<FlatPanel> unfold_panels(const PanelMesh& mesh, const UnfoldParams& params = {});

// Signed dihedral (degrees) between triangles (a,b,c) and (a,d,b) sharing
// edge a-b, both counter-clockwise: 0 when coplanar, positive for a valley
// (d lies on the side the normal of (a,b,c) points to).
double fold_angle_deg(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

}  // namespace tessella
