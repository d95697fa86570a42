#include "tessella/panel_classes.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "tessella/errors.h"

namespace tessella {

double panel_warp(const std::vector<Vec3>& p) {
  if (p.size() < 4) return 0.0;
  if (p.size() == 4) {
    const Vec3 d1 = p[2] - p[0], d2 = p[3] - p[1];
    const Vec3 n = d1.cross(d2);
    if (!(n.norm() > 1e-300)) return 0.0;
    return std::abs((p[1] - p[0]).dot(n)) / n.norm();
  }
  Vec3 c = Vec3::Zero();
  for (const Vec3& q : p) c += q;
  c /= static_cast<double>(p.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3& q : p) cov += (q - c) * (q - c).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Vec3 normal = eig.eigenvectors().col(0);
  double worst = 0;
  for (const Vec3& q : p) worst = std::max(worst, std::abs((q - c).dot(normal)));
  return 2.0 * worst;
}

PanelClasses classify_panels(const PanelMesh& mesh, const PanelClassParams& params) {
  std::vector<std::vector<Vec3>> panels(mesh.panels.size());
  for (std::size_t k = 0; k < panels.size(); ++k)
    for (int v : mesh.panels[k]) panels[k].push_back(mesh.xyz[static_cast<std::size_t>(v)]);
  return classify_panels(panels, params);
}

PanelClasses classify_panels(const std::vector<std::vector<Vec3>>& panels,
                             const PanelClassParams& params) {
  require_in_range("flat_tolerance (mm)", params.flat_tolerance, 1e-9, 1e9);
  require_in_range("cold_bend_ratio", params.cold_bend_ratio, 0.0, 1.0);
  require_in_range("cold_bend_warp (mm)", params.cold_bend_warp, 0.0, 1e9);
  PanelClasses out;
  const std::size_t n = panels.size();
  out.label.resize(n);
  out.warp.resize(n);
  out.limit.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::vector<Vec3>& pts = panels[k];
    const double warp = panel_warp(pts);
    double span = 0;
    for (std::size_t i = 0; i < pts.size(); ++i)
      for (std::size_t j = i + 1; j < pts.size(); ++j)
        span = std::max(span, (pts[i] - pts[j]).norm());
    const double limit =
        params.cold_bend_warp > 0 ? params.cold_bend_warp : params.cold_bend_ratio * span;
    const PanelClass c = warp <= params.flat_tolerance ? PanelClass::Flat
                         : warp <= limit               ? PanelClass::ColdBent
                                                       : PanelClass::Curved;
    out.label[k] = static_cast<int>(c);
    out.warp[k] = warp;
    out.limit[k] = limit;
    ++out.count[static_cast<std::size_t>(c)];
  }
  return out;
}

}  // namespace tessella
