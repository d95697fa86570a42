// Family regularization (issue 17, part 2): small node moves that make the
// panels of each family congruent within a tighter tolerance, so that one
// template really serves the whole family.
//
// Families are grouped as panel_families() groups them (at family_tolerance).
// Each round, every family's mean shape is found (its members brought onto
// its template by their best rigid fit and averaged), placed on every member
// by that member's fit, and every free node moves to the mean of the places
// its panels ask of it; then it is held within max_deviation of the surface
// (moved back along the line to its closest surface point). Nodes on the
// face's boundary and the nodes of boundary pieces (panels with trim points,
// modelled on their trims) stay where they are, so boundary nodes stay on
// their trims. Rounds stop when every family's members lie within
// `tolerance` of its template, when the largest move falls under 1e-6 of the
// model size, or after max_iterations. Deterministic.
#pragma once

#include "tessella/panel_mesh.h"
#include "tessella/surface_face.h"

namespace tessella {

struct FamilyRegularizationParams {
  double family_tolerance = 2.0;  // mm, families as panel_families() groups them; > 0
  double tolerance = 0.5;         // mm, the congruence sought; in (0, family_tolerance]
  double max_deviation = 0.0;     // mm, how far a node may leave the surface; > 0, required
  bool mirror = true;             // a template may serve its mirror image
  int max_iterations = 50;
};

struct FamilyRegularizationReport {
  int families = 0;  // at family_tolerance (the grouping regularized)
  // Families at `tolerance` before and after: how many the moves removed.
  int families_before = 0, families_after = 0;
  // Largest distance of a member to its family's template, before and after.
  double max_error_before = 0, max_error_after = 0;
  double max_move = 0;            // mm, the largest node move
  double max_node_deviation = 0;  // mm, the largest distance of a moved node to the surface
  int moved_nodes = 0;            // nodes moved by more than 1e-9 of the model size
  int iterations = 0;
};

// The mesh with its nodes moved (xyz and uv: uv is the closest surface
// point's). Throws InvalidParameter for a bad parameter.
PanelMesh regularize_families(const SurfaceFace& face, const PanelMesh& mesh,
                              const FamilyRegularizationParams& params,
                              FamilyRegularizationReport* report = nullptr);

}  // namespace tessella
