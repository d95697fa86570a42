// Panel types: flat panels that are congruent within tolerances share a type.
//
// A panel's signature is its flat outline read corner by corner: the length of
// the edge leaving corner i and the signed turning angle at corner i (degrees,
// from the edge entering the corner to the edge leaving it), plus its fold
// angle. Two panels match when they have as many corners, their fold angles
// differ by at most `angle_tol`, and some cyclic shift of the corners (the
// panel turned in its plane) brings every edge length within `length_tol` and
// every turning angle within `angle_tol`. Mirror images do not match (the
// corner order is never reversed: front and back differ).
//
// Grouping is greedy in panel order: a panel joins the first type (lowest
// index) whose representative - its first panel - it matches, else it starts
// a new type. Types are numbered in order of first appearance. Every member
// is within tolerance of its representative (two members may differ by up to
// twice the tolerance). A panel with no corners or a non-finite length or
// angle matches nothing (a type of its own).
//
// Cost: O(n log n) for n panels when few representatives crowd one
// tolerance cell (candidates are looked up by corner count, longest and
// shortest edge and fold angle, all necessary conditions of a match).
#pragma once

#include <vector>

#include "tessella/unfold.h"
#include "tessella/vec.h"

namespace tessella {

struct PanelTypeParams {
  double length_tol = 1.0;  // mm, edge lengths
  double angle_tol = 0.5;   // degrees, turning angles and fold angle
};

struct PanelTypes {
  std::vector<int> type;            // per panel, 0-based, numbered by first appearance
  std::vector<int> representative;  // per type: its first panel
  int count() const { return static_cast<int>(representative.size()); }
};

// outlines[p]: the flat corners of panel p in its order; fold_deg[p]: its fold
// angle in degrees (same size). Throws InvalidParameter for a negative or
// non-finite tolerance or mismatched sizes.
PanelTypes panel_types(const std::vector<std::vector<Vec2>>& outlines,
                       const std::vector<double>& fold_deg, const PanelTypeParams& params = {});

// The fold angle of an unfolded panel as types compare it: the largest
// |angle| among its folds (0 without folds).
double type_fold_angle(const FlatPanel& flat);

// Types of unfolded panels (unfold_panels), fold angle by type_fold_angle.
PanelTypes panel_types(const std::vector<FlatPanel>& flat, const PanelTypeParams& params = {});

// Types of a mesh's panels: unfold_panels(mesh, unfold), then the above.
PanelTypes panel_types(const PanelMesh& mesh, const UnfoldParams& unfold,
                       const PanelTypeParams& params = {});

}  // namespace tessella
