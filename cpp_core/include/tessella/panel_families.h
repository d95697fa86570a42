// Panel families: panels that one template serves within a tolerance.
//
// Where panel types (panel_types.h) group congruent panels, families group
// panels that differ from a shared template by at most `tolerance`: the
// largest corner-to-corner distance (mm) after a rigid alignment of the panel
// onto the template. One template (a drawing, a mould, a CNC program) then
// serves every member of its family.
//
// Distance of panel B to panel A: infinite unless they have as many corners;
// otherwise the least, over the corner correspondences (every cyclic shift of
// B's corners; with `mirror` also every shift of the reversed order), of the
// largest corner distance after the Kabsch alignment of B onto A (rotation and
// translation; with `mirror` also a reflection). Kabsch minimises the RMS
// corner distance, not the largest one, so the reported distance is an upper
// bound of the minimax distance over rigid motions: a panel reported within
// the tolerance is within it (conservatively). The distance is symmetric.
//
// Grouping, deterministic (same input, same output, bit for bit):
//   0. twins: a panel within 1e-3 x tolerance of a lower-indexed panel is
//      handled with it (repeated panels cost n, not n^2, comparisons); when
//      more than `max_pairs` candidate pairs remain (a tolerance far above the
//      panels' differences), the twin radius grows to tolerance / 32, / 16,
//      / 8 or / 4, the first that leaves at most max_pairs (coarse grouping:
//      near-linear cost, a cover at tolerance - radius among the groups, so
//      possibly more families than the full cover);
//   1. candidate pairs are pruned by necessary conditions (same corner count,
//      diameters and sorted corner-distance lists within 2 x tolerance);
//   2. greedy set cover: the panel that covers the most panels not yet covered
//      (within the tolerance of it) becomes a template, ties by lowest index,
//      until every panel is covered (a ln(n) approximation of the fewest
//      families); templates made redundant by later ones are dropped, and
//      two templates whose exclusive panels one panel covers are replaced by
//      it (2-for-1 swaps, within a work bound);
//   3. each panel joins the template nearest to it; then in each family the
//      template becomes the member whose largest distance to the other members
//      is least (only members that cover the whole family), and 3 repeats
//      until nothing changes (at most a few rounds).
// Families are numbered by their lowest panel index. Every panel is within
// `tolerance` of its family's template: error[p] <= tolerance.
//
// Cost: O(n log n + m) for n panels and m candidate pairs (pairs of similar
// size); 5,000 quads in a few tens of milliseconds (bench/bench_families.cpp).
#pragma once

#include <vector>

#include "tessella/vec.h"

namespace tessella {

struct PanelFamilyParams {
  double tolerance = 2.0;  // mm, largest corner distance to the template; > 0
  bool mirror = true;      // a template may serve its mirror image (turned over)
  // Candidate pairs (of similar panels) measured before the coarse grouping
  // takes over (see panel_families); 0 = automatic, max(400000, 64 n).
  long long max_pairs = 0;
};

struct PanelFamilies {
  std::vector<int> labels;        // per panel: its family, 0-based, by lowest member
  std::vector<int> templates;     // per family: the panel index of its template
  std::vector<double> max_error;  // per family: the largest error of its members
  std::vector<double> error;      // per panel: its distance to its family's template
  // Panels within this of a lower-indexed one were grouped with it first:
  // 1e-3 x tolerance, or tolerance / 32 ... / 4 in the coarse grouping.
  double twin_radius = 0.0;
  int count() const { return static_cast<int>(templates.size()); }
};

// panels[p]: the 3D corners of panel p in order. Throws InvalidParameter for a
// tolerance that is not > 0 and finite (or above 1e9), InvalidGeometry for a
// panel with fewer than 3 corners or a non-finite coordinate.
PanelFamilies panel_families(const std::vector<std::vector<Vec3>>& panels,
                             const PanelFamilyParams& params = {});

// The distance of panel b to panel a as panel_families measures it (the
// largest corner distance after the best alignment found; +infinity when the
// corner counts differ).
double panel_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b, bool mirror);

}  // namespace tessella
