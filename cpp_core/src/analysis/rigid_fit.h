// The rigid motion that best places one outline on another (Kabsch), and the
// corner correspondence of a panel to a template that serves it best: what
// family regularization moves panels towards.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "tessella/vec.h"

namespace tessella {

struct RigidMotion {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // det -1: a reflection
  Vec3 translation = Vec3::Zero();
  Vec3 operator()(const Vec3& x) const { return rotation * x + translation; }
};

// The least-squares rigid motion taking from[i] onto to[i] (Kabsch, via the
// SVD of the cross-covariance); a reflection only if `reflect` allows it.
RigidMotion kabsch(const std::vector<Vec3>& from, const std::vector<Vec3>& to, bool reflect);

// How a template serves a panel of as many corners: order[i] is the panel
// corner matched to template corner i (a cyclic shift of the panel's corners,
// with `mirror` also of their reverse), `motion` places the template on the
// panel, `error` is the largest corner distance then. The order with the
// least error wins (ties: the first shift, forward before reversed).
struct TemplateFit {
  std::vector<int> order;
  RigidMotion motion;
  double error = 0;
};
TemplateFit fit_template(const std::vector<Vec3>& templ, const std::vector<Vec3>& panel,
                         bool mirror);

}  // namespace tessella
