#include "tessella/panel_metrics.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "tessella/errors.h"
#include "mesh/panel_model.h"
#include "tessella/progress.h"
#include "tessella/surface_face.h"

namespace tessella {

namespace {

constexpr double kPi = 3.14159265358979323846;

double mean_edge(const std::vector<Vec3>& p) {
  double sum = 0;
  for (std::size_t k = 0; k < p.size(); ++k) sum += (p[(k + 1) % p.size()] - p[k]).norm();
  return sum / double(p.size());
}

double planarity(const std::vector<Vec3>& p) {
  const double edge = mean_edge(p);
  if (p.size() < 4 || edge <= 0) return 0.0;
  if (p.size() == 4) {
    // Distance between the diagonals as skew lines.
    const Vec3 d1 = p[2] - p[0], d2 = p[3] - p[1];
    const Vec3 n = d1.cross(d2);
    if (n.norm() <= 1e-300) return 0.0;
    return std::abs((p[1] - p[0]).dot(n)) / n.norm() / edge;
  }
  Vec3 c = Vec3::Zero();
  for (const Vec3& q : p) c += q;
  c /= double(p.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3& q : p) cov += (q - c) * (q - c).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Vec3 normal = eig.eigenvectors().col(0);
  double worst = 0;
  for (const Vec3& q : p) worst = std::max(worst, std::abs((q - c).dot(normal)));
  return worst / edge;
}

}  // namespace

double panel_model_deviation(const SurfaceFace& face, const std::vector<Vec3>& p,
                             const std::vector<Vec2>& uv,
                             const std::vector<std::array<int, 3>>& tris, int samples) {
  double worst = 0;
  auto probe = [&](const Vec3& x, const Vec2& start) {
    worst = std::max(worst, face.project(x, start).distance);
  };
  if (tris.empty()) {
    const int n = samples;
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; j <= n; ++j) {
        const double s = double(i) / n, t = double(j) / n;
        const double w0 = (1 - s) * (1 - t), w1 = s * (1 - t), w2 = s * t, w3 = (1 - s) * t;
        probe(w0 * p[0] + w1 * p[1] + w2 * p[2] + w3 * p[3],
              w0 * uv[0] + w1 * uv[1] + w2 * uv[2] + w3 * uv[3]);
      }
    }
    return worst;
  }
  // Triangle or flat pieces: each triangle sampled as densely as its size
  // asks (a boundary panel has many thin triangles).
  double extent = 0;
  for (const Vec3& a : p)
    for (const Vec3& b : p) extent = std::max(extent, (a - b).norm());
  for (const auto& t : tris) {
    const double longest = std::max(
        {(p[t[0]] - p[t[1]]).norm(), (p[t[1]] - p[t[2]]).norm(), (p[t[2]] - p[t[0]]).norm()});
    const int n = std::max(1, static_cast<int>(std::ceil(samples * longest / extent)));
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) {
        const double s = double(i) / n, r = double(j) / n, q = 1 - s - r;
        probe(q * p[t[0]] + s * p[t[1]] + r * p[t[2]], q * uv[t[0]] + s * uv[t[1]] + r * uv[t[2]]);
      }
    }
  }
  return worst;
}

namespace {

void measure_panel(const SurfaceFace& face, const PanelMesh& mesh, std::size_t k, int samples,
                   PanelMetrics& m, std::size_t slot) {
  const auto& panel = mesh.panels[k];
  std::vector<Vec3> p;
  for (int v : panel) p.push_back(mesh.xyz[v]);
  const std::vector<Vec2> uv = panel_corner_uv(mesh, k);
  // One triangulation for the deviation and the area (an outline along a trim
  // has hundreds of points).
  const std::vector<std::array<int, 3>> tris = panel_model_triangles(mesh, k);
  m.deviation[slot] = panel_model_deviation(face, p, uv, tris, samples);
  m.planarity[slot] = planarity(p);
  if (tris.empty()) {
    m.area[slot] = panel_area(mesh, k);  // the bilinear quad
  } else {
    double area = 0;
    for (const auto& t : tris) area += 0.5 * (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).norm();
    m.area[slot] = area;
  }
  double lo = 180.0, hi = 0.0;
  for (std::size_t c = 0; c < p.size(); ++c) {
    const Vec3 a = p[(c + p.size() - 1) % p.size()] - p[c];
    const Vec3 b = p[(c + 1) % p.size()] - p[c];
    const double angle = std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / kPi;
    lo = std::min(lo, angle);
    hi = std::max(hi, angle);
  }
  m.min_angle[slot] = lo;
  m.max_angle[slot] = hi;
}

void resize(PanelMetrics& m, std::size_t np) {
  m.deviation.resize(np);
  m.planarity.resize(np);
  m.area.resize(np);
  m.min_angle.resize(np);
  m.max_angle.resize(np);
}

void measure_rods(const PanelMesh& mesh, PanelMetrics& m) {
  m.rod_length.clear();
  m.rod_length.reserve(mesh.rods.size());
  for (const auto& rod : mesh.rods)
    m.rod_length.push_back((mesh.xyz[rod[0]] - mesh.xyz[rod[1]]).norm());
}

}  // namespace

PanelMetrics measure_panels(const SurfaceFace& face, const PanelMesh& mesh,
                            const MetricsParams& params) {
  require_in_range("samples", params.samples, 1, 64);
  PanelMetrics m;
  const std::size_t np = mesh.panels.size();
  resize(m, np);
  for (std::size_t k = 0; k < np; ++k) {
    report_progress(double(k) / double(np), "measuring panels");
    measure_panel(face, mesh, k, params.samples, m, k);
  }
  measure_rods(mesh, m);
  return m;
}

PanelMetrics measure_panels(const SurfaceFace& face, const PanelMesh& mesh,
                            const MetricsParams& params, const std::vector<char>& which) {
  require_in_range("samples", params.samples, 1, 64);
  if (which.size() != mesh.panels.size())
    throw InvalidParameter("measure_panels: one flag per panel expected");
  PanelMetrics m;
  const std::size_t np = mesh.panels.size();
  resize(m, np);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t k = 0; k < np; ++k) {
    report_progress(double(k) / double(np), "measuring panels");
    if (which[k])
      measure_panel(face, mesh, k, params.samples, m, k);
    else
      m.deviation[k] = m.planarity[k] = m.area[k] = m.min_angle[k] = m.max_angle[k] = nan;
  }
  measure_rods(mesh, m);
  return m;
}

PanelMetrics remeasure_panels(const SurfaceFace& face, const PanelMesh& mesh,
                              const PanelMetrics& before, const std::vector<int>& origin,
                              const std::vector<char>& changed, const MetricsParams& params) {
  require_in_range("samples", params.samples, 1, 64);
  const std::size_t np = mesh.panels.size();
  if (origin.size() != np || changed.size() != np)
    throw InvalidParameter("remeasure_panels: origin and changed must have one entry per panel");
  PanelMetrics m;
  resize(m, np);
  for (std::size_t k = 0; k < np; ++k) {
    if (changed[k]) {
      measure_panel(face, mesh, k, params.samples, m, k);
      continue;
    }
    const std::size_t o = static_cast<std::size_t>(origin[k]);
    m.deviation[k] = before.deviation.at(o);
    m.planarity[k] = before.planarity.at(o);
    m.area[k] = before.area.at(o);
    m.min_angle[k] = before.min_angle.at(o);
    m.max_angle[k] = before.max_angle.at(o);
  }
  measure_rods(mesh, m);
  return m;
}

SummaryStats summarize(const std::vector<double>& values) {
  SummaryStats s;
  s.count = int(values.size());
  if (values.empty()) return s;
  s.min = *std::min_element(values.begin(), values.end());
  s.max = *std::max_element(values.begin(), values.end());
  double sum = 0;
  for (double v : values) sum += v;
  s.mean = sum / values.size();
  double sq = 0;
  for (double v : values) sq += (v - s.mean) * (v - s.mean);
  s.variance = sq / values.size();
  return s;
}

std::vector<bool> irregular_panels(const PanelMesh& mesh, const PanelMetrics& metrics,
                                   const IrregularParams& params) {
  require_in_range("min_angle", params.min_angle_deg, 0.0, 180.0);
  require_in_range("min_area_fraction", params.min_area_fraction, 0.0, 1.0);
  std::vector<bool> flags(mesh.panels.size());
  for (std::size_t k = 0; k < mesh.panels.size(); ++k) {
    flags[k] = static_cast<int>(mesh.panels[k].size()) != mesh.regular_corners ||
               metrics.min_angle[k] < params.min_angle_deg ||
               metrics.area[k] < params.min_area_fraction * mesh.nominal_area;
  }
  return flags;
}

}  // namespace tessella
