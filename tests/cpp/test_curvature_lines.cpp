// curvature_lines (issue 16): the principal directions against closed forms,
// and the method's quads on a surface of revolution (its principal lines are
// the meridians and parallels, whose quads are planar).
#include <gtest/gtest.h>

#include <BRepBuilderAPI_MakeFace.hxx>
#include <GeomAPI_PointsToBSplineSurface.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <cmath>

#include "methods/boundary_driven/principal_field.h"
#include "tessella/boundary_driven.h"
#include "tessella/panelize.h"
#include "test_faces.h"

namespace tessella {
namespace {

constexpr double kPi = 3.14159265358979323846;

// z = a x^2 + b y^2 over the square [-L, L]^2 of (s, t), turned by phi:
// x = s cos phi - t sin phi, y = s sin phi + t cos phi (an interpolated bicubic).
SurfaceFace turned_paraboloid(double a, double b, double phi, double L) {
  const int n = 21;
  TColgp_Array2OfPnt pts(1, n, 1, n);
  for (int i = 1; i <= n; ++i)
    for (int j = 1; j <= n; ++j) {
      const double s = -L + 2 * L * (i - 1) / (n - 1), t = -L + 2 * L * (j - 1) / (n - 1);
      const double x = s * std::cos(phi) - t * std::sin(phi);
      const double y = s * std::sin(phi) + t * std::cos(phi);
      pts(i, j) = gp_Pnt(x, y, a * x * x + b * y * y);
    }
  GeomAPI_PointsToBSplineSurface fit;
  fit.Interpolate(pts);
  return SurfaceFace::from_brep_string(
      test::brep(BRepBuilderAPI_MakeFace(fit.Surface(), 1e-7).Face()));
}

// A funnel: radius 800 + 4200 (i/8)^2.5 at height 750 i, half a turn
// (meridians along u, parallels along v), interpolated.
SurfaceFace funnel() {
  TColgp_Array2OfPnt pts(1, 9, 1, 13);
  for (int i = 0; i < 9; ++i) {
    const double r = 800.0 + 4200.0 * std::pow(i / 8.0, 2.5);
    for (int j = 0; j < 13; ++j)
      pts(i + 1, j + 1) = gp_Pnt(r * std::cos(kPi * j / 12), r * std::sin(kPi * j / 12), 750.0 * i);
  }
  GeomAPI_PointsToBSplineSurface fit;
  fit.Interpolate(pts);
  return SurfaceFace::from_brep_string(
      test::brep(BRepBuilderAPI_MakeFace(fit.Surface(), 1e-7).Face()));
}

TEST(CurvatureLines, PrincipalDirectionOfATurnedParaboloid) {
  // At the apex the principal directions are x and y, at -phi from du; the
  // curvatures 2a and 2b.
  const double a = 1.0 / 20000, b = 1.0 / 8000, phi = 20.0 * kPi / 180;
  const SurfaceFace face = turned_paraboloid(a, b, phi, 3000.0);
  const UvBounds bd = face.bounds();
  double aniso = 0;
  const Vec2 c =
      principal_cross(face, Vec2(0.5 * (bd.u_min + bd.u_max), 0.5 * (bd.v_min + bd.v_max)), aniso);
  EXPECT_NEAR(aniso, 2 * std::abs(a - b), 0.01 * 2 * std::abs(a - b));
  EXPECT_NEAR(c.x(), std::cos(-4 * phi), 0.01);
  EXPECT_NEAR(c.y(), std::sin(-4 * phi), 0.01);
}

TEST(CurvatureLines, MeridiansAreLinesOfCurvatureOfASurfaceOfRevolution) {
  const SurfaceFace face = funnel();
  const UvBounds bd = face.bounds();
  for (double fu : {0.2, 0.5, 0.8})
    for (double fv : {0.2, 0.5, 0.8}) {
      double aniso = 0;
      const Vec2 c = principal_cross(
          face, Vec2(bd.u_min + fu * (bd.u_max - bd.u_min), bd.v_min + fv * (bd.v_max - bd.v_min)),
          aniso);
      EXPECT_GT(aniso, 0);
      // du (the meridian) is principal: 4 theta = 0 (to the interpolation's
      // accuracy: within a degree).
      EXPECT_NEAR(std::atan2(c.y(), c.x()) / 4, 0.0, kPi / 180) << fu << " " << fv;
    }
}

}  // namespace
}  // namespace tessella
