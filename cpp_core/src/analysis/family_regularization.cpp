#include "tessella/family_regularization.h"

#include <algorithm>
#include <cmath>

#include "analysis/rigid_fit.h"
#include "mesh/fixed_vertices.h"
#include "tessella/errors.h"
#include "tessella/panel_families.h"

namespace tessella {

namespace {

std::vector<std::vector<Vec3>> corner_points(const PanelMesh& mesh,
                                             const std::vector<std::vector<int>>& corners) {
  std::vector<std::vector<Vec3>> out;
  out.reserve(corners.size());
  for (const auto& c : corners) {
    std::vector<Vec3> x;
    for (int v : c) x.push_back(mesh.xyz[static_cast<std::size_t>(v)]);
    out.push_back(std::move(x));
  }
  return out;
}

// Largest distance of a member to its family's template.
double worst_error(const std::vector<std::vector<Vec3>>& x, const PanelFamilies& f, bool mirror) {
  double worst = 0;
  for (std::size_t p = 0; p < x.size(); ++p) {
    const int t = f.templates[static_cast<std::size_t>(f.labels[p])];
    if (static_cast<std::size_t>(t) == p) continue;
    worst = std::max(worst, fit_template(x[static_cast<std::size_t>(t)], x[p], mirror).error);
  }
  return worst;
}

}  // namespace

PanelMesh regularize_families(const SurfaceFace& face, const PanelMesh& mesh,
                              const FamilyRegularizationParams& params,
                              FamilyRegularizationReport* report) {
  require_in_range("family_tolerance (mm)", params.family_tolerance, 1e-9, 1e9);
  require_in_range("tolerance (mm)", params.tolerance, 1e-9, params.family_tolerance);
  if (params.max_deviation == 0.0) throw InvalidParameter("max_deviation (mm) is required");
  require_in_range("max_deviation (mm)", params.max_deviation, 1e-9, 1e9);
  require_in_range("max_iterations", params.max_iterations, 0, 10000);
  FamilyRegularizationReport rep;
  PanelMesh out = mesh;
  // Thousands of projections close together: the span-cached evaluation.
  const SurfaceFace::FastEvaluation fast(face);
  // A panel's corners: its outline's vertices in order (trim points too, as
  // panel_families compares outlines: a boundary piece's cut shape).
  const std::vector<std::vector<int>>& corners = mesh.panels;
  std::vector<std::vector<Vec3>> x = corner_points(out, corners);
  const PanelFamilies families =
      panel_families(x, PanelFamilyParams{params.family_tolerance, params.mirror});
  rep.families = families.count();
  rep.families_before =
      panel_families(x, PanelFamilyParams{params.tolerance, params.mirror}).count();
  rep.max_error_before = worst_error(x, families, params.mirror);
  std::vector<std::vector<int>> members(static_cast<std::size_t>(families.count()));
  for (std::size_t p = 0; p < corners.size(); ++p)
    members[static_cast<std::size_t>(families.labels[p])].push_back(static_cast<int>(p));
  const std::vector<char> fixed = fixed_vertices(mesh);
  const double tiny = 1e-6 * face.model_size();
  std::vector<Vec3> sum(out.vertex_count());
  std::vector<int> count(out.vertex_count());
  double error = rep.max_error_before;
  double best_error = error;
  int best_tight = rep.families_before;
  PanelMesh best = out;
  for (int round = 0; round < params.max_iterations && error > params.tolerance; ++round) {
    rep.iterations = round + 1;
    std::fill(sum.begin(), sum.end(), Vec3::Zero());
    std::fill(count.begin(), count.end(), 0);
    for (std::size_t f = 0; f < members.size(); ++f) {
      const std::vector<int>& m = members[f];
      if (m.size() < 2) continue;
      const std::vector<Vec3>& t = x[static_cast<std::size_t>(families.templates[f])];
      // The mean shape in the template's place: members fitted onto it.
      std::vector<TemplateFit> fits;
      std::vector<Vec3> mean(t.size(), Vec3::Zero());
      for (int p : m) {
        fits.push_back(fit_template(t, x[static_cast<std::size_t>(p)], params.mirror));
        const TemplateFit& fit = fits.back();
        const Eigen::Matrix3d back = fit.motion.rotation.transpose();
        for (std::size_t i = 0; i < t.size(); ++i)
          mean[i] +=
              back * (x[static_cast<std::size_t>(p)][static_cast<std::size_t>(fit.order[i])] -
                      fit.motion.translation);
      }
      for (Vec3& c : mean) c /= static_cast<double>(m.size());
      // The mean shape placed on each member: where its corners should be.
      for (std::size_t k = 0; k < m.size(); ++k) {
        const std::size_t p = static_cast<std::size_t>(m[k]);
        std::vector<Vec3> matched;
        for (int i : fits[k].order) matched.push_back(x[p][static_cast<std::size_t>(i)]);
        const RigidMotion place = kabsch(mean, matched, params.mirror);
        for (std::size_t i = 0; i < mean.size(); ++i) {
          const int v = corners[p][static_cast<std::size_t>(fits[k].order[i])];
          sum[static_cast<std::size_t>(v)] += place(mean[i]);
          ++count[static_cast<std::size_t>(v)];
        }
      }
    }
    double moved = 0;
    for (std::size_t v = 0; v < out.vertex_count(); ++v) {
      if (fixed[v] || count[v] == 0) continue;
      // Half way (a node between families gets conflicting places: a full
      // step oscillates).
      Vec3 target = 0.5 * (out.xyz[v] + sum[v] / count[v]);
      // Within max_deviation of the surface: back towards the closest point.
      const Projection foot = face.project(target, out.uv[v]);
      const Vec3 off = target - foot.point;
      if (off.norm() > params.max_deviation)
        target = foot.point + off * (params.max_deviation / off.norm());
      moved = std::max(moved, (target - out.xyz[v]).norm());
      out.xyz[v] = target;
      out.uv[v] = foot.uv;
    }
    x = corner_points(out, corners);
    error = worst_error(x, families, params.mirror);
    // Keep the round with the fewest families at `tolerance` (the figure a
    // workshop prices; a node between two families may keep one member's
    // error up, so the largest error is no guide).
    const int tight = panel_families(x, PanelFamilyParams{params.tolerance, params.mirror}).count();
    if (tight < best_tight) best_tight = tight, best_error = error, best = out;
    if (moved < tiny) break;
  }
  out = std::move(best);
  rep.max_error_after = best_error;
  rep.families_after = best_tight;
  for (std::size_t v = 0; v < out.vertex_count(); ++v) {
    const double move = (out.xyz[v] - mesh.xyz[v]).norm();
    if (move <= 1e-9 * face.model_size()) continue;
    ++rep.moved_nodes;
    rep.max_move = std::max(rep.max_move, move);
    rep.max_node_deviation =
        std::max(rep.max_node_deviation, face.project(out.xyz[v], out.uv[v]).distance);
  }
  if (report) *report = rep;
  return out;
}

}  // namespace tessella
