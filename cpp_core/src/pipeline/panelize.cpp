// The pipeline (tessella/panelize.h): method -> short rods merged -> metrics ->
// irregular panels -> nodes -> folds -> summary, the same steps for every method.
#include "tessella/panelize.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <utility>

#include "analysis/coverage.h"
#include "common/parallel_chunks.h"
#include "mesh/boundary_pieces.h"
#include "mesh/panel_model.h"
#include "mesh/short_rod_merge.h"
#include "mesh/sliver_merge.h"
#include "pipeline/stages.h"
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

// Sum over panels of deviation x perimeter (mm^2): how much larger than the
// surface they cover the panel models may be (check_coverage).
double deviation_band(const PanelMesh& mesh, const PanelMetrics& metrics) {
  double band = 0;
  for (std::size_t k = 0; k < mesh.panels.size(); ++k) {
    const auto& p = mesh.panels[k];
    double perimeter = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
      perimeter += (mesh.xyz[p[(i + 1) % p.size()]] - mesh.xyz[p[i]]).norm();
    if (std::isfinite(metrics.deviation[k])) band += metrics.deviation[k] * perimeter;
  }
  return band;
}

// Refuses a walking_agent result over its bound (after the retries).
void check_hard_bound(const PanelMetrics& metrics, double bound) {
  int over = 0;
  double worst = 0;
  for (double d : metrics.deviation) {
    if (!(d <= bound)) ++over;
    if (std::isfinite(d)) worst = std::max(worst, d);
  }
  if (over == 0) return;
  throw GeometryFailure("walking_agent: " + std::to_string(over) +
                        " panel(s) deviate more than max_deviation = " + std::to_string(bound) +
                        " mm (largest " + std::to_string(worst) +
                        " mm, measured densely): the bound cannot be met on this face; raise "
                        "max_deviation or max_refinements");
}

}  // namespace

double largest(const std::vector<double>& values) {
  double worst = 0;
  for (double d : values)
    if (std::isfinite(d)) worst = std::max(worst, d);
  return worst;
}

double param_number(const ParamValues& values, const MethodDeclaration& method,
                    const std::string& name) {
  return value_or<double>(values, method, name);
}

Modelled run_method(const SurfaceFace& face, const MethodDeclaration& decl,
                    const ParamValues& values) {
  return run_method_with(face, decl, values, [&] { return decl.run(face, values); });
}

Modelled run_method_with(const SurfaceFace& face, const MethodDeclaration& decl,
                         const ParamValues& values, const std::function<PanelMesh()>& make) {
  const std::string& method = decl.name;
  Modelled out;
  face.reset_evaluations();
  const auto started = std::chrono::steady_clock::now();
  out.mesh = make();
  // No method returns a panel without area (collinear or repeated corners).
  out.zero_area = remove_zero_area_panels(out.mesh, face.model_size());
  // No rod shorter than min_rod_length, whatever the method; walking_agent's
  // max_deviation is a hard bound on every panel and is kept (gradient_descent's
  // is a target).
  report_stage(0.0, "merging short rods");
  ShortRodMergeParams sp;
  sp.min_rod_length = value_or<double>(values, decl, "min_rod_length");
  sp.samples = value_or<int>(values, decl, "samples");
  // boundary_driven's point is an all-quad layout: a collapse may not make a triangle.
  sp.keep_quads = method == "boundary_driven" || method == "curvature_lines";
  if (method == "walking_agent") sp.max_deviation = value_or<double>(values, decl, "max_deviation");
  out.merged = merge_short_rods(face, out.mesh, sp);
  // No panel tapering to a knife edge at a trim (a grid line meeting an
  // opening's rim nearly along it): merged across its rod into a neighbour,
  // a piece of at most five nodes (bent at most twice). The clipped grids
  // only, where it was measured (bench/boundary_outlines.py): walking_agent's
  // union could break its hard bound, boundary_driven keeps its rods off
  // such corners itself, and the guide-line layouts' rows are their point.
  if (method == "iso_grid" || method == "equal_size_grid" || method == "chebyshev_net")
    out.mesh.merged_spikes = merge_spikes(out.mesh, kSpikeCornerDeg, 5);
  out.core_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  out.evaluations = face.evaluations();
  return out;
}

namespace {

BoundaryPiecesParams boundary_pieces_params(const ParamValues& values,
                                            const MethodDeclaration& decl, double allowed,
                                            double min_rod_length) {
  const std::string& method = decl.name;
  BoundaryPiecesParams bp;
  bp.max_deviation = allowed;
  // boundary_driven's point is an all-quad layout: its boundary quads are
  // bent along a diagonal, not refined with new trim nodes (which would make
  // them pentagons and split them), unless boundary_deviation asks for it.
  if ((method == "boundary_driven" || method == "curvature_lines") &&
      !(value_or<double>(values, decl, "boundary_deviation") > 0)) {
    bp.max_deviation = 0;
    bp.may_add_nodes = false;
  }
  bp.samples = value_or<int>(values, decl, "samples");
  // New nodes on the trim keep min_rod_length from the others.
  bp.min_node_spacing = min_rod_length;
  bp.hard_bound =
      method == "walking_agent" && !(value_or<double>(values, decl, "boundary_deviation") > 0);
  return bp;
}

}  // namespace

int promote_hard_bound_trim_nodes(const SurfaceFace& face, const MethodDeclaration& decl,
                                  const ParamValues& values, Modelled& m) {
  if (m.mesh.is_node.empty()) return 0;  // every vertex is a node already
  // A hard bound is a given number: no metrics of the full panels needed.
  const BoundaryPiecesParams bp =
      boundary_pieces_params(values, decl, allowed_boundary_deviation(values, decl, PanelMetrics{}),
                             m.merged.min_rod_length);
  if (!bp.hard_bound || !(bp.max_deviation > 0)) return 0;
  PanelMesh trial = m.mesh;
  model_boundary_pieces(face, trial, bp);
  int promoted = 0;
  const std::size_t n = std::min(m.mesh.is_node.size(), trial.is_node.size());
  for (std::size_t v = 0; v < n; ++v)
    if (!m.mesh.is_node[v] && trial.is_node[v]) m.mesh.is_node[v] = 1, ++promoted;
  return promoted;
}

void model_and_measure(const SurfaceFace& face, const MethodDeclaration& decl,
                       const ParamValues& values, Modelled& out) {
  const auto metrics_started = std::chrono::steady_clock::now();
  MetricsParams mp;
  mp.samples = value_or<int>(values, decl, "samples");
  mp.threads = out.metrics_threads_requested;
  report_stage(0.0, "measuring panels");
  // Full panels first (they fix the boundary pieces' allowance), then the
  // boundary pieces once they are modelled.
  std::vector<char> full(out.mesh.panels.size());
  for (std::size_t k = 0; k < full.size(); ++k) full[k] = modelled_as_pieces(out.mesh, k) ? 0 : 1;
  const PanelMetrics full_metrics = measure_panels(face, out.mesh, mp, full);
  const BoundaryPiecesParams bp =
      boundary_pieces_params(values, decl, allowed_boundary_deviation(values, decl, full_metrics),
                             out.merged.min_rod_length);
  report_stage(0.0, "modelling boundary pieces");
  out.pieces = model_boundary_pieces(face, out.mesh, bp);
  for (std::size_t k = 0; k < out.pieces.changed.size(); ++k)
    if (!full[static_cast<std::size_t>(out.pieces.origin[k])]) out.pieces.changed[k] = 1;
  out.metrics =
      remeasure_panels(face, out.mesh, full_metrics, out.pieces.origin, out.pieces.changed, mp);
  out.metrics_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - metrics_started).count();
  out.metrics_threads = worker_threads(mp.threads);
}

namespace {

Modelled model_panels(const SurfaceFace& face, const MethodDeclaration& decl,
                      const ParamValues& values) {
  Modelled out = run_method(face, decl, values);
  model_and_measure(face, decl, values, out);
  return out;
}

// Runs of walking_agent with a tightened bound before it is refused.
constexpr int kHardBoundRetries = 3;

}  // namespace

PanelizeResult panelize(std::shared_ptr<const SurfaceFace> face, const std::string& method,
                        const ParamValues& values) {
  if (!face) throw InvalidGeometry("panelize: no face");
  const MethodDeclaration& decl = method_declaration(method);
  check_param_values(decl, values);
  // The whole pipeline evaluates through the span caches (the method's own
  // scopes and the metrics' workers nest inside this one).
  const SurfaceFace::FastEvaluation fast(*face);

  face->reset_global_projections();
  const auto started = std::chrono::steady_clock::now();
  Modelled m = model_panels(*face, decl, values);
  if (method == "walking_agent") {
    // walking_agent's max_deviation is a hard bound, kept on the pipeline's own
    // measure (an upper bound within 1%), not on the method's estimate: where
    // a panel came out over it (the estimate samples coarser; a boundary piece
    // bends), the run is repeated with the bound tightened by the ratio found.
    const double bound = value_or<double>(values, decl, "max_deviation");
    ParamValues tighter = values;
    double effective = bound;
    for (int retry = 0; retry < kHardBoundRetries; ++retry) {
      const double worst = largest(m.metrics.deviation);
      if (worst <= bound) break;
      effective *= 0.98 * bound / worst;
      tighter["max_deviation"] = effective;
      report_stage(0.0, "tightening max_deviation");
      m = model_panels(*face, decl, tighter);
    }
    check_hard_bound(m.metrics, bound);
  }
  return finish_result(face, decl, values, std::move(m), started);
}

PanelizeResult finish_result(std::shared_ptr<const SurfaceFace> face, const MethodDeclaration& decl,
                             const ParamValues& values, Modelled&& m,
                             std::chrono::steady_clock::time_point started) {
  const std::string& method = decl.name;
  PanelizeResult r;
  r.face = face;
  r.method = method;
  r.mesh = std::move(m.mesh);
  r.metrics = std::move(m.metrics);
  r.summary.zero_area_panels = m.zero_area;
  r.summary.core_seconds = m.core_seconds;
  r.summary.metrics_seconds = m.metrics_seconds;
  r.summary.metrics_threads = m.metrics_threads;
  r.summary.surface_evaluations = m.evaluations;
  r.summary.bend_count = m.pieces.bends;
  r.summary.split_panels = m.pieces.split;
  r.summary.boundary_nodes_added = m.pieces.refined;
  const ShortRodMergeReport& merged = m.merged;

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
  s.merged_spikes = r.mesh.merged_spikes;
  for (bool b : r.irregular) s.irregular_count += b ? 1 : 0;
  int quads = 0;
  // A quad is a panel of four nodes (outline points along a trim do not count).
  for (const auto& p : r.mesh.panels) {
    int corners = 0;
    for (int v : p) corners += is_node(r.mesh, v) ? 1 : 0;
    quads += corners == 4 ? 1 : 0;
  }
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

  report_stage(0.0, "checking coverage");
  Coverage coverage = measure_coverage(*face, r.mesh, r.metrics.area);
  s.gap_fraction = coverage.gap_fraction();
  s.overlap_fraction = coverage.overlap_fraction();
  s.model_area_ratio = coverage.face_area > 0 ? coverage.model_area / coverage.face_area : 0.0;
  if (m.coverage_allowance > 0) {
    // A face of a set: its shared edges run as chords (what the neighbour's
    // panels meet); the strips between them and the edges are no hole. The
    // figures above stay as measured.
    coverage.gap = std::max(0.0, coverage.gap - m.coverage_allowance);
    const double beyond = std::max(0.0, coverage.overlap + coverage.outside - m.coverage_allowance);
    const double share = coverage.overlap + coverage.outside > 0
                             ? beyond / (coverage.overlap + coverage.outside)
                             : 0.0;
    coverage.overlap *= share;
    coverage.outside *= share;
  }
  if (decl.tiles_face) {
    check_coverage(coverage, deviation_band(r.mesh, r.metrics), method);
  } else if (coverage.gap_fraction() > kMaxCoverageError ||
             coverage.overlap_fraction() > kMaxCoverageError) {
    s.coverage_warning = coverage_message(coverage, method);
  }
  s.global_projections = face->global_projections();
  s.pipeline_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return r;
}

PanelizeResult remeasured_result(const PanelizeResult& r, PanelMesh mesh, int samples) {
  if (!r.face)
    throw InvalidParameter("the result has no face (a face set): give one face's result");
  if (mesh.vertex_count() != r.mesh.vertex_count() || mesh.panels != r.mesh.panels)
    throw InvalidParameter(
        "remeasured_result: the mesh must keep the result's vertices and panels");
  const MethodDeclaration& decl = method_declaration(r.method);
  const SurfaceFace& face = *r.face;
  const SurfaceFace::FastEvaluation fast(face);
  PanelizeResult out;
  out.face = r.face;
  out.method = r.method;
  out.mesh = std::move(mesh);
  MetricsParams mp;
  mp.samples = samples;
  out.metrics = measure_panels(face, out.mesh, mp);
  IrregularParams ip;
  ip.min_angle_deg = value_or<double>({}, decl, "min_angle");
  ip.min_area_fraction = value_or<double>({}, decl, "sliver_fraction");
  out.irregular = irregular_panels(out.mesh, out.metrics, ip);
  out.nodes = node_data(face, out.mesh);
  out.fold_angle = fold_angles(out.mesh);
  PanelizeSummary& s = out.summary;
  s = r.summary;
  s.irregular_count = 0;
  for (bool b : out.irregular) s.irregular_count += b ? 1 : 0;
  s.deviation = summarize(out.metrics.deviation);
  s.unreliable_deviation = 0;
  for (char u : out.metrics.deviation_unreliable) s.unreliable_deviation += u ? 1 : 0;
  s.planarity = summarize(out.metrics.planarity);
  s.area = summarize(out.metrics.area);
  s.rod_length = summarize(out.metrics.rod_length);
  s.short_rods = 0;
  for (double length : out.metrics.rod_length) s.short_rods += length < s.min_rod_length ? 1 : 0;
  s.shortest_rod = s.rod_length.count > 0 ? s.rod_length.min : 0.0;
  return out;
}

}  // namespace tessella
