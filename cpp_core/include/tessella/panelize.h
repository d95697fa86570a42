// The whole pipeline in one call: method -> short rods merged -> metrics ->
// folds -> summary. Python, the C++ tests and the benchmarks all run it.
//
// Progress and cancel: install a ProgressScope (progress.h) on the calling
// thread; every stage reports through it and a sink returning false throws
// Cancelled between (and inside) stages, for every method.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tessella/methods.h"
#include "tessella/panel_mesh.h"
#include "tessella/panel_metrics.h"

namespace tessella {

class SurfaceFace;

struct PanelizeSummary {
  int panel_count = 0, rod_count = 0, node_count = 0;
  int merged_slivers = 0, merged_spikes = 0, irregular_count = 0, fold_count = 0;
  double quad_share = 0.0;  // fraction of panels that are quads
  // Boundary pieces (src/mesh/boundary_pieces.h): bend lines over all panels,
  // panels split by a new rod, trim points made nodes to meet the allowance.
  int bend_count = 0, split_panels = 0, boundary_nodes_added = 0;
  double nominal_area = 0.0, face_area = 0.0, model_size = 0.0;
  // Cost of the method call alone (no metrics).
  std::uint64_t surface_evaluations = 0;
  double core_seconds = 0.0;
  // Whole run (method and metrics): projections where Newton failed and the
  // global search answered (costly on big surfaces: should stay rare).
  std::uint64_t global_projections = 0;
  // Time of the metrics and boundary-piece stages, and the threads measuring.
  double metrics_seconds = 0.0;
  int metrics_threads = 1;
  double pipeline_seconds = 0.0;  // the whole panelize() call
  SummaryStats deviation, planarity, area, rod_length;
  // Panels whose deviation is an upper bound without a foot point found
  // (PanelMetrics::deviation_unreliable).
  int unreliable_deviation = 0;
  // The short-rod stage (min_rod_length): the limit it used (mm, the
  // automatic one if min_rod_length = 0), the rods it collapsed, the rods
  // still under the limit (no valid collapse) and the shortest rod left (mm).
  double min_rod_length = 0.0;
  int merged_rods = 0, short_rods = 0;
  double shortest_rod = 0.0;
  // Coverage of the face (src/analysis/coverage.h), as shares of the face
  // area: uncovered, covered twice or outside the trims, and the panels' 3D
  // area over the face area. Checked before panelize returns.
  double gap_fraction = 0.0, overlap_fraction = 0.0, model_area_ratio = 0.0;
  // Methods that need not tile the face (MethodDeclaration::tiles_face):
  // what is wrong with its coverage, empty if within 0.1%.
  std::string coverage_warning;
  // Panels of (next to) no area merged into a neighbour or dropped.
  int zero_area_panels = 0;
};

struct PanelizeResult {
  // The face the panels were built on: unfolding and flattening reuse it
  // (no second BRep parse).
  std::shared_ptr<const SurfaceFace> face;
  std::string method;
  PanelMesh mesh;
  PanelMetrics metrics;
  std::vector<bool> irregular;     // per panel
  NodeData nodes;                  // per vertex
  std::vector<double> fold_angle;  // degrees, one per mesh.folds entry (0 = flat)
  PanelizeSummary summary;
};

// Runs `method` (method_declarations()) with `values` on `face`. Throws
// InvalidParameter for a bad parameter, InvalidGeometry for an unusable face,
// LimitExceeded above max_panels, Cancelled when the progress sink says stop.
PanelizeResult panelize(std::shared_ptr<const SurfaceFace> face, const std::string& method,
                        const ParamValues& values = {});

// The result with its nodes moved (`mesh`: the same vertices and panels,
// new positions; family regularization, planarization): metrics (`samples`
// per edge), irregular panels, node normals, fold angles and the summary's
// figures measured again; its counts, coverage and timings kept. Throws
// InvalidParameter for a face set's combined result or a mesh of other panels.
PanelizeResult remeasured_result(const PanelizeResult& r, PanelMesh mesh, int samples = 8);

}  // namespace tessella
