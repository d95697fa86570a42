// The pipeline (tessella/panelize.h): method -> short rods merged -> metrics ->
// irregular panels -> nodes -> folds -> summary, the same steps for every method.
#include "tessella/panelize.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <utility>

#include "common/parallel_chunks.h"
#include "mesh/boundary_pieces.h"
#include "mesh/panel_model.h"
#include "mesh/short_rod_merge.h"
#include "tessella/errors.h"
#include "tessella/progress.h"
#include "tessella/surface_face.h"

namespace tessella {

namespace {

template <class T>
T value_or(const ParamValues& values, const MethodDeclaration& method, const std::string& name) {
  const auto it = values.find(name);
  const ParamValue& v = it != values.end() ? it->second : method.find(name)->default_value;
  if (const double* x = std::get_if<double>(&v)) return static_cast<T>(*x);
  if (const int* x = std::get_if<int>(&v)) return static_cast<T>(*x);
  if (const bool* x = std::get_if<bool>(&v)) return static_cast<T>(*x);
  throw InvalidParameter(name + " must be a number");
}

Vec3 unit_normal(const PanelMesh& mesh, const std::vector<int>& tri) {
  const Vec3& p0 = mesh.xyz[tri[0]];
  const Vec3 c = (mesh.xyz[tri[1]] - p0).cross(mesh.xyz[tri[2]] - p0);
  return c / c.norm();
}

// Angle (degrees, 0 = flat) between the two triangles on each fold diagonal;
// NaN where the fold is not shared by exactly two triangles.
std::vector<double> fold_angles(const PanelMesh& mesh) {
  std::vector<double> out;
  if (mesh.folds.empty()) return out;
  std::map<std::pair<int, int>, std::vector<int>> by_edge;
  for (std::size_t k = 0; k < mesh.panels.size(); ++k) {
    const std::vector<int>& p = mesh.panels[k];
    if (p.size() != 3) continue;
    for (int i = 0; i < 3; ++i) {
      const int a = p[i], b = p[(i + 1) % 3];
      by_edge[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(k));
    }
  }
  for (const auto& f : mesh.folds) {
    const auto it = by_edge.find({f[0], f[1]});
    if (it == by_edge.end() || it->second.size() != 2) {
      out.push_back(std::nan(""));
      continue;
    }
    const Vec3 n0 = unit_normal(mesh, mesh.panels[it->second[0]]);
    const Vec3 n1 = unit_normal(mesh, mesh.panels[it->second[1]]);
    const double d = std::min(1.0, std::max(-1.0, n0.dot(n1)));
    out.push_back(std::acos(d) * (180.0 / M_PI));
  }
  return out;
}

// The deviation a flat boundary piece may keep (BoundaryPiecesParams):
// boundary_deviation if given, else the method's own bound, else the largest
// deviation of the full panels (a boundary piece no worse than the panels
// the layout already accepts).
double allowed_boundary_deviation(const ParamValues& values, const MethodDeclaration& method,
                                  const PanelMetrics& full) {
  const double given = value_or<double>(values, method, "boundary_deviation");
  if (given > 0) return given;
  if (method.find("max_deviation")) {
    const double bound = value_or<double>(values, method, "max_deviation");
    if (bound > 0) return bound;
  }
  double worst = 0;
  for (double d : full.deviation)
    if (std::isfinite(d)) worst = std::max(worst, d);
  return worst;
}

}  // namespace

PanelizeResult panelize(std::shared_ptr<const SurfaceFace> face, const std::string& method,
                        const ParamValues& values) {
  if (!face) throw InvalidGeometry("panelize: no face");
  const MethodDeclaration& decl = method_declaration(method);
  check_param_values(decl, values);

  PanelizeResult r;
  r.face = face;
  r.method = method;
  face->reset_evaluations();
  face->reset_global_projections();
  const auto started = std::chrono::steady_clock::now();
  r.mesh = decl.run(*face, values);
  // No rod shorter than min_rod_length, whatever the method; walking_agent's
  // max_deviation is a hard bound on every panel and is kept (gradient_descent's
  // is a target).
  report_stage(0.0, "merging short rods");
  ShortRodMergeParams sp;
  sp.min_rod_length = value_or<double>(values, decl, "min_rod_length");
  sp.samples = value_or<int>(values, decl, "samples");
  // boundary_driven's point is an all-quad layout: a collapse may not make a triangle.
  sp.keep_quads = method == "boundary_driven";
  if (method == "walking_agent")
    sp.max_deviation = value_or<double>(values, decl, "max_deviation");
  const ShortRodMergeReport merged = merge_short_rods(*face, r.mesh, sp);
  r.summary.core_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  r.summary.surface_evaluations = face->evaluations();

  const auto metrics_started = std::chrono::steady_clock::now();
  MetricsParams mp;
  mp.samples = value_or<int>(values, decl, "samples");
  report_stage(0.0, "measuring panels");
  // Full panels first (they fix the boundary pieces' allowance), then the
  // boundary pieces once they are modelled.
  std::vector<char> full(r.mesh.panels.size());
  for (std::size_t k = 0; k < full.size(); ++k) full[k] = modelled_as_pieces(r.mesh, k) ? 0 : 1;
  const PanelMetrics full_metrics = measure_panels(*face, r.mesh, mp, full);
  BoundaryPiecesParams bp;
  bp.max_deviation = allowed_boundary_deviation(values, decl, full_metrics);
  bp.samples = mp.samples;
  // New nodes on the trim keep min_rod_length from the others.
  bp.min_node_spacing = merged.min_rod_length;
  bp.hard_bound = method == "walking_agent" && !(value_or<double>(values, decl, "boundary_deviation") > 0);
  report_stage(0.0, "modelling boundary pieces");
  BoundaryPiecesReport pieces = model_boundary_pieces(*face, r.mesh, bp);
  for (std::size_t k = 0; k < pieces.changed.size(); ++k)
    if (!full[static_cast<std::size_t>(pieces.origin[k])]) pieces.changed[k] = 1;
  r.metrics = remeasure_panels(*face, r.mesh, full_metrics, pieces.origin, pieces.changed, mp);
  r.summary.metrics_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - metrics_started).count();
  r.summary.metrics_threads = worker_threads(mp.threads);
  r.summary.bend_count = pieces.bends;
  r.summary.split_panels = pieces.split;
  r.summary.boundary_nodes_added = pieces.refined;

  IrregularParams ip;
  ip.min_angle_deg = value_or<double>(values, decl, "min_angle");
  ip.min_area_fraction = value_or<double>(values, decl, "sliver_fraction");
  r.irregular = irregular_panels(r.mesh, r.metrics, ip);
  r.nodes = node_data(*face, r.mesh);
  r.fold_angle = fold_angles(r.mesh);

  PanelizeSummary& s = r.summary;
  s.panel_count = static_cast<int>(r.mesh.panels.size());
  s.rod_count = static_cast<int>(r.mesh.rods.size());
  for (std::size_t v = 0; v < r.mesh.xyz.size(); ++v)
    if (is_node(r.mesh, static_cast<int>(v))) ++s.node_count;
  s.merged_slivers = r.mesh.merged_slivers;
  for (bool b : r.irregular) s.irregular_count += b ? 1 : 0;
  int quads = 0;
  for (const auto& p : r.mesh.panels) quads += p.size() == 4 ? 1 : 0;
  s.quad_share = r.mesh.panels.empty() ? 0.0 : double(quads) / double(r.mesh.panels.size());
  s.nominal_area = r.mesh.nominal_area;
  s.face_area = face->area();
  s.model_size = face->model_size();
  s.fold_count = static_cast<int>(r.mesh.folds.size());
  s.deviation = summarize(r.metrics.deviation);
  for (char u : r.metrics.deviation_unreliable) s.unreliable_deviation += u ? 1 : 0;
  s.planarity = summarize(r.metrics.planarity);
  s.area = summarize(r.metrics.area);
  s.rod_length = summarize(r.metrics.rod_length);
  s.min_rod_length = merged.min_rod_length;
  s.merged_rods = merged.merged;
  // Still under the limit after both stages (no valid collapse).
  for (double length : r.metrics.rod_length) s.short_rods += length < merged.min_rod_length ? 1 : 0;
  s.shortest_rod = s.rod_length.count > 0 ? s.rod_length.min : 0.0;
  s.global_projections = face->global_projections();
  s.pipeline_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return r;
}

}  // namespace tessella
