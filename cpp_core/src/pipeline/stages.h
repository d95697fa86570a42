// The pipeline's stages (tessella/panelize.h) one by one, for a caller that
// runs them on several faces and works on the meshes in between (a face set
// makes the nodes of shared edges agree after the method, before the metrics).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mesh/boundary_pieces.h"
#include "mesh/short_rod_merge.h"
#include "tessella/methods.h"
#include "tessella/panelize.h"

namespace tessella {

// One run of the method and the stages that shape its panels: zero-area
// panels, short rods, metrics, boundary pieces (the metrics of the pieces as
// modelled).
struct Modelled {
  PanelMesh mesh;
  PanelMetrics metrics;
  ShortRodMergeReport merged;
  BoundaryPiecesReport pieces;
  int zero_area = 0;
  double core_seconds = 0;  // the method and the short rods, not the metrics
  double metrics_seconds = 0;
  int metrics_threads_requested = 0;  // 0: every core (MetricsParams::threads)
  int metrics_threads = 1;
  std::uint64_t evaluations = 0;
  // Face sets: the area (mm^2) the chords along shared edges leave out of the
  // face or add beyond it, allowed by the coverage check.
  double coverage_allowance = 0.0;
};

// The largest finite value (0 for none): a result's worst deviation.
double largest(const std::vector<double>& values);

// A number parameter's value, or its declared default.
double param_number(const ParamValues& values, const MethodDeclaration& method,
                    const std::string& name);

// The method, zero-area panels removed, short rods merged.
Modelled run_method(const SurfaceFace& face, const MethodDeclaration& decl,
                    const ParamValues& values);

// The same with the method's mesh made by `make` (boundary_driven on faces of
// one surface: from curves traced on their union).
Modelled run_method_with(const SurfaceFace& face, const MethodDeclaration& decl,
                         const ParamValues& values, const std::function<PanelMesh()>& make);

// Metrics, boundary pieces, the pieces' metrics (on out.mesh as it is).
void model_and_measure(const SurfaceFace& face, const MethodDeclaration& decl,
                       const ParamValues& values, Modelled& out);

// Under a hard deviation bound (walking_agent's), the trim points the boundary
// pieces stage would make nodes, made nodes now: a face set joins its faces
// along shared edges before that stage, and a node it added after the join
// would stand on one side of the edge only (without it a boundary panel of
// the split roof measured 52 mm against a bound of 30, and its whole face was
// walked again at a tighter bound: 78% more panels). Returns how many.
int promote_hard_bound_trim_nodes(const SurfaceFace& face, const MethodDeclaration& decl,
                                  const ParamValues& values, Modelled& m);

// Irregular panels, nodes, folds, summary and the coverage check.
PanelizeResult finish_result(std::shared_ptr<const SurfaceFace> face, const MethodDeclaration& decl,
                             const ParamValues& values, Modelled&& m,
                             std::chrono::steady_clock::time_point started);

}  // namespace tessella
