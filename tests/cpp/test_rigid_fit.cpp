// Rigid fits (analysis/rigid_fit.h): Kabsch recovers a known motion, and a
// template finds its panel's corner order (turned, or reversed when mirrored).
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/rigid_fit.h"

namespace tessella {
namespace {

std::vector<Vec3> quad() {
  return {Vec3(0, 0, 0), Vec3(1200, 0, 40), Vec3(1300, 900, 0), Vec3(-100, 800, 60)};
}

TEST(RigidFit, KabschRecoversAKnownMotion) {
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Vec3 shift(500, -200, 3000);
  std::vector<Vec3> moved;
  for (const Vec3& p : quad()) moved.push_back(rot * p + shift);
  const RigidMotion m = kabsch(quad(), moved, false);
  EXPECT_LT((m.rotation - rot).norm(), 1e-12);
  EXPECT_LT((m.translation - shift).norm(), 1e-9);
}

TEST(RigidFit, TemplateFindsTheTurnedAndTheMirroredOrder) {
  const std::vector<Vec3> t = quad();
  // The same quad, corners turned by one.
  const std::vector<Vec3> turned = {t[1], t[2], t[3], t[0]};
  const TemplateFit a = fit_template(t, turned, false);
  EXPECT_LT(a.error, 1e-9);
  EXPECT_EQ(a.order, (std::vector<int>{3, 0, 1, 2}));
  // Its mirror image (x -> -x): only with mirror allowed.
  std::vector<Vec3> mirrored;
  for (const Vec3& p : t) mirrored.push_back(Vec3(-p.x(), p.y(), p.z()));
  EXPECT_LT(fit_template(t, mirrored, true).error, 1e-9);
  EXPECT_GT(fit_template(t, mirrored, false).error, 1.0);
  // Different corner counts never fit.
  EXPECT_TRUE(std::isinf(fit_template(t, {t[0], t[1], t[2]}, true).error));
}

}  // namespace
}  // namespace tessella
