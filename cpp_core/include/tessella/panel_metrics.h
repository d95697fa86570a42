// Per-panel and per-rod measurements against the surface (see DESIGN.md glossary).
// The panel a workshop builds is modelled as: triangle -> flat triangle,
// quad of four nodes -> bilinear patch of its corners, any other panel -> its
// flat pieces (src/mesh/panel_model.h, src/mesh/boundary_pieces.h), trim edge
// included. Every figure here is measured on that model.
#pragma once

#include <array>
#include <vector>

#include "tessella/panel_mesh.h"

namespace tessella {

struct MetricsParams {
  // Samples per panel edge direction (quad: n x n; each fan triangle: n(n+1)/2).
  int samples = 8;
  // Threads measuring panels (0: TESSELLA_THREADS, else every core). Each
  // panel's figures are the same bit for bit for any count.
  int threads = 0;
};

struct PanelMetrics {
  // Max distance panel model -> surface (mm): an upper bound of the true
  // distance, within 1% of it (measure_panel_deviation).
  std::vector<double> deviation;
  // 1 where the farthest point's projection found no foot point (Newton and
  // OCCT's Extrema both failed: deviation is then the distance to the
  // nearest surface point found, maybe not tight), or where the check
  // between the samples ran out of splits (the maximum may lie higher).
  std::vector<char> deviation_unreliable;
  std::vector<double> planarity;  // quad: diagonal distance / mean edge; n-gon: max
                                  // distance to best-fit plane / mean edge; triangle: 0
  std::vector<double> area;       // mm^2, of the panel model above
  std::vector<double> min_angle;  // degrees, 3D corner angles
  std::vector<double> max_angle;
  std::vector<double> rod_length;  // mm, in mesh.rods order
};

PanelMetrics measure_panels(const SurfaceFace& face, const PanelMesh& mesh,
                            const MetricsParams& params = {});

// Largest distance from a panel model to the surface: corners `p` with their
// (u,v) (projection starts), `tris` its flat triangles (empty: the bilinear
// patch of a quad). A grid of `samples` per edge direction (at least 2: the
// edge midpoints; each triangle as many as its size asks), projected in order
// of a cheap upper bound down to 70% of the largest distance found (flat
// pieces: also down to the third largest of the pieces' own largest, below
// which no sample can be the largest or one of the three seeds; samples whose
// bound is within 1e-9 of the model size lie on the face: after the first, not
// projected). On a bilinear quad: where neighbouring samples near the top
// disagree with their own gradients (the distance is creased, its nearest
// surface point jumping from one sheet to another, or it varies faster than
// the grid; two samples on the face agree) a grid three times as fine; then,
// unless the largest sample lies on the face, from every local maximum of the
// grid within 70% of the
// largest (at most 8) a Newton ascent on the distance (its gradient from the
// foot point, a rank-one Hessian update, borders held; to 1e-6 in s, t),
// restarted if its top turns out to lie on a wrong sheet, and where it stops
// on a crease a pattern search along it and a 5 x 5 look-around. On flat
// pieces a pattern search (to h / 128) from the three largest samples.
// Every distance is that of a true surface point, so each probe is an upper
// bound of the distance at its point of the panel. Then the check between
// the samples: where the surface's second derivatives can be bounded (its
// control net: B-spline, Bezier; closed forms: plane, cylinder, cone,
// sphere, torus), an upper bound of the distance over every cell of the
// sampling shows that no point of the panel lies more than 1% (plus 1e-5 of
// the panel's size) farther than the value; a cell that does not show it is
// split and its new points probed, within an allowance (256 splits and eight
// per cell). With a verified foot point at the farthest point and the check
// passed (reliable), the value is the true maximum within 1% (tested
// against independent dense re-measures on closed forms, a wrinkled
// surface, narrow bumps and narrow dips; bench/metric_trust.py re-measures
// every panel). A Newton run that stops at a foot point farther than a known
// surface point is retried from the nearest corner and then by the global
// search. `unreliable` is set if the farthest point still has no verified
// foot point (the value is then the nearest surface point's distance) or
// the check ran out of splits (the maximum may lie higher).
struct PanelDeviation {
  double value = 0;
  bool unreliable = false;
  Vec3 at = Vec3::Zero();  // the point of the panel model where the value is taken
};
PanelDeviation measure_panel_deviation(const SurfaceFace& face, const std::vector<Vec3>& p,
                                       const std::vector<Vec2>& uv,
                                       const std::vector<std::array<int, 3>>& tris, int samples);
// Same, the value only.
double panel_model_deviation(const SurfaceFace& face, const std::vector<Vec3>& p,
                             const std::vector<Vec2>& uv,
                             const std::vector<std::array<int, 3>>& tris, int samples);

// Only the panels with which[k] set (one flag per panel); the others NaN.
PanelMetrics measure_panels(const SurfaceFace& face, const PanelMesh& mesh,
                            const MetricsParams& params, const std::vector<char>& which);

// Metrics after a stage changed some panels: panel k of `mesh` is measured
// again if changed[k], else copied from panel origin[k] of `before`.
PanelMetrics remeasure_panels(const SurfaceFace& face, const PanelMesh& mesh,
                              const PanelMetrics& before, const std::vector<int>& origin,
                              const std::vector<char>& changed, const MetricsParams& params = {});

struct SummaryStats {
  int count = 0;
  double mean = 0, variance = 0, min = 0, max = 0;
};
SummaryStats summarize(const std::vector<double>& values);

struct IrregularParams {
  double min_angle_deg = 30.0;      // a corner under this makes a panel irregular
  double min_area_fraction = 0.25;  // of mesh.nominal_area
};
// Irregular panel: not of the layout's regular_corners (a quad, or a triangle in a
// triangular layout), or a corner angle under the limit, or an area under
// the fraction of the nominal area. Returns one flag per panel.
std::vector<bool> irregular_panels(const PanelMesh& mesh, const PanelMetrics& metrics,
                                   const IrregularParams& params = {});

}  // namespace tessella
