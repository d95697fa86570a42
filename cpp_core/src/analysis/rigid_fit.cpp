#include "analysis/rigid_fit.h"

#include <limits>

namespace tessella {

RigidMotion kabsch(const std::vector<Vec3>& from, const std::vector<Vec3>& to, bool reflect) {
  const std::size_t n = std::min(from.size(), to.size());
  RigidMotion m;
  if (n == 0) return m;
  Vec3 a = Vec3::Zero(), b = Vec3::Zero();
  for (std::size_t i = 0; i < n; ++i) a += from[i], b += to[i];
  a /= static_cast<double>(n), b /= static_cast<double>(n);
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < n; ++i) h += (from[i] - a) * (to[i] - b).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  // A proper rotation unless a reflection is allowed (and fits better).
  if (!reflect && (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0) d(2, 2) = -1;
  m.rotation = svd.matrixV() * d * svd.matrixU().transpose();
  m.translation = b - m.rotation * a;
  return m;
}

TemplateFit fit_template(const std::vector<Vec3>& templ, const std::vector<Vec3>& panel,
                         bool mirror) {
  TemplateFit best;
  best.error = std::numeric_limits<double>::infinity();
  const int n = static_cast<int>(templ.size());
  if (n == 0 || static_cast<int>(panel.size()) != n) return best;
  std::vector<Vec3> matched(static_cast<std::size_t>(n));
  std::vector<int> order(static_cast<std::size_t>(n));
  for (int reversed = 0; reversed <= (mirror ? 1 : 0); ++reversed) {
    for (int shift = 0; shift < n; ++shift) {
      for (int i = 0; i < n; ++i) {
        const int k = reversed ? ((shift - i) % n + n) % n : (shift + i) % n;
        order[static_cast<std::size_t>(i)] = k;
        matched[static_cast<std::size_t>(i)] = panel[static_cast<std::size_t>(k)];
      }
      const RigidMotion m = kabsch(templ, matched, mirror);
      double error = 0;
      for (int i = 0; i < n; ++i)
        error = std::max(
            error,
            (m(templ[static_cast<std::size_t>(i)]) - matched[static_cast<std::size_t>(i)]).norm());
      if (error < best.error) best = {order, m, error};
    }
  }
  return best;
}

}  // namespace tessella
