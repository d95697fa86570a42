// Unfold, nest and outline offset: closed-form checks.
#include <gtest/gtest.h>

#include <cmath>

#include "tessella/errors.h"
#include "tessella/flatten.h"
#include "tessella/nest.h"
#include "tessella/outline_offset.h"
#include "tessella/unfold.h"
#include "test_faces.h"

using namespace tessella;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<Vec2> uv_square() { return {{0, 0}, {1, 0}, {1, 1}, {0, 1}}; }

}  // namespace

TEST(Unfold, PlanarQuadKeepsEdgesAndHasNoFold) {
  // A planar, rotated rectangle 300 x 200.
  const Vec3 o(10, 20, 30), ex = Vec3(1, 1, 0).normalized(), ey = Vec3(0, 0, 1);
  std::vector<Vec3> xyz{o, o + 300 * ex, o + 300 * ex + 200 * ey, o + 200 * ey};
  const FlatPanel f = unfold_panel(xyz, uv_square());
  ASSERT_EQ(f.outline.size(), 4u);
  EXPECT_TRUE(f.folds.empty());
  EXPECT_NEAR(f.outline[0].norm(), 0.0, 1e-12);
  EXPECT_NEAR(f.outline[1].x(), 300.0, 1e-9);
  EXPECT_NEAR(f.outline[1].y(), 0.0, 1e-9);
  EXPECT_NEAR(f.outline[2].x(), 300.0, 1e-9);
  EXPECT_NEAR(f.outline[2].y(), 200.0, 1e-9);  // counter-clockwise
  EXPECT_NEAR(f.outline[3].x(), 0.0, 1e-9);
  EXPECT_NEAR(f.u_direction.x(), 1.0, 1e-9);
}

TEST(Unfold, BentQuadFoldsAboutTheDiagonalWithTheSmallerFold) {
  // Unit square with corner 2 lifted by h: diagonal 1-3 has triangles
  // (1,2,3) bent and (1,3,0) flat; diagonal 0-2 splits the lift evenly.
  const double s = 1000, h = 100;
  std::vector<Vec3> xyz{{0, 0, 0}, {s, 0, 0}, {s, s, h}, {0, s, 0}};
  const FlatPanel f = unfold_panel(xyz, uv_square());
  ASSERT_EQ(f.folds.size(), 1u);
  // Independent: the normals of both splits.
  auto angle = [](Vec3 n1, Vec3 n2) {
    return std::acos(n1.normalized().dot(n2.normalized())) * 180 / kPi;
  };
  const double a02 =
      angle((xyz[1] - xyz[0]).cross(xyz[2] - xyz[0]), (xyz[2] - xyz[0]).cross(xyz[3] - xyz[0]));
  const double a13 =
      angle((xyz[2] - xyz[1]).cross(xyz[3] - xyz[1]), (xyz[3] - xyz[1]).cross(xyz[0] - xyz[1]));
  const bool use02 = a02 <= a13;
  EXPECT_EQ(f.folds[0].a, use02 ? 0 : 1);
  EXPECT_EQ(f.folds[0].b, use02 ? 2 : 3);
  ASSERT_EQ(f.triangles.size(), 2u);
  EXPECT_NEAR(std::abs(f.folds[0].angle_deg), std::min(a02, a13), 1e-9);
  // Every edge and the fold diagonal keep their 3D lengths.
  for (int i = 0; i < 4; ++i)
    EXPECT_NEAR((f.outline[(i + 1) % 4] - f.outline[i]).norm(), (xyz[(i + 1) % 4] - xyz[i]).norm(),
                1e-9);
  const int a = f.folds[0].a, b = f.folds[0].b;
  EXPECT_NEAR((f.outline[b] - f.outline[a]).norm(), (xyz[b] - xyz[a]).norm(), 1e-9);
}

TEST(Unfold, FoldSignValleyAndMountain) {
  // Triangles (a,b,c) and (a,d,b) over the edge a-b on the x axis, c at +y.
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0.5, 1, 0);
  EXPECT_NEAR(fold_angle_deg(a, b, c, Vec3(0.5, -1, 1)), 45.0, 1e-9);    // d toward +z: valley
  EXPECT_NEAR(fold_angle_deg(a, b, c, Vec3(0.5, -1, -1)), -45.0, 1e-9);  // mountain
  EXPECT_NEAR(fold_angle_deg(a, b, c, Vec3(0.5, -1, 0)), 0.0, 1e-12);
}

TEST(Unfold, PlanarPentagonExact) {
  // Regular pentagon, radius 500, tilted plane.
  std::vector<Vec3> xyz;
  std::vector<Vec2> uv;
  for (int k = 0; k < 5; ++k) {
    const double t = 2 * kPi * k / 5;
    uv.emplace_back(std::cos(t), std::sin(t));
    xyz.emplace_back(500 * std::cos(t), 500 * std::sin(t) * 0.6, 500 * std::sin(t) * 0.8);
  }
  const FlatPanel f = unfold_panel(xyz, uv);
  EXPECT_TRUE(f.folds.empty());
  for (int i = 0; i < 5; ++i)
    for (int j = i + 1; j < 5; ++j)
      EXPECT_NEAR((f.outline[i] - f.outline[j]).norm(), (xyz[i] - xyz[j]).norm(), 1e-9);
  EXPECT_GT(polygon_area(f.outline), 0.0);
}

TEST(Unfold, RejectsDegenerate) {
  std::vector<Vec3> xyz{{0, 0, 0}, {0, 0, 0}, {1, 1, 0}};
  EXPECT_THROW(unfold_panel(xyz, {{0, 0}, {1, 0}, {0, 1}}), InvalidGeometry);
  UnfoldParams p;
  p.fold_tolerance_deg = -1;
  EXPECT_THROW(unfold_panel({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 0}, {1, 0}, {0, 1}}, p),
               InvalidParameter);
}

namespace {

std::vector<Vec2> placed(const std::vector<Vec2>& o, const NestPlacement& pl) {
  const double a = pl.angle_deg * kPi / 180, c = std::cos(a), s = std::sin(a);
  std::vector<Vec2> out;
  for (const Vec2& p : o)
    out.emplace_back(c * p.x() - s * p.y() + pl.offset.x(), s * p.x() + c * p.y() + pl.offset.y());
  return out;
}

}  // namespace

TEST(Nest, RectanglesFillASheetExactly) {
  // 8 parts 496 x 245 fit a 1000 x 1000 sheet as 2 x 4 with spacing 6 (2 mm to spare).
  std::vector<std::vector<Vec2>> parts(8, {{0, 0}, {496, 0}, {496, 245}, {0, 245}});
  NestParams p;
  p.sheet_width = 1000, p.sheet_height = 1000, p.margin = 0, p.spacing = 6, p.rotations = 1;
  const NestLayout layout = nest_parts(parts, p);
  for (std::size_t i = 0; i < parts.size(); ++i)
    for (const Vec2& q : placed(parts[i], layout.placements[i])) {
      EXPECT_GE(q.x(), -1e-9);
      EXPECT_LE(q.x(), 1000 + 1e-9);
      EXPECT_GE(q.y(), -1e-9);
      EXPECT_LE(q.y(), 1000 + 1e-9);
    }
  EXPECT_EQ(layout.sheet_count, 1);
  EXPECT_NEAR(layout.utilization, 8 * 496 * 245 / 1e6, 1e-12);
}

TEST(Nest, DeterministicAndErrors) {
  std::vector<std::vector<Vec2>> parts{{{0, 0}, {300, 0}, {0, 400}}, {{0, 0}, {200, 0}, {100, 90}}};
  NestParams p;
  p.sheet_width = 1000, p.sheet_height = 500;
  const NestLayout a = nest_parts(parts, p), b = nest_parts(parts, p);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    EXPECT_EQ(a.placements[i].sheet, b.placements[i].sheet);
    EXPECT_EQ(a.placements[i].offset, b.placements[i].offset);
    EXPECT_EQ(a.placements[i].angle_deg, b.placements[i].angle_deg);
  }
  p.sheet_height = 350;  // the 300 x 400 triangle fits only rotated
  EXPECT_NO_THROW(nest_parts(parts, p));
  p.rotations = 1;
  EXPECT_THROW(nest_parts(parts, p), InvalidParameter);
  p.rotations = 4;
  p.spacing = -1;
  EXPECT_THROW(nest_parts(parts, p), InvalidParameter);
}

TEST(OutlineOffset, SquareGrowsByTheDistance) {
  OutlineOffsetParams p;
  p.distance = 2.0;
  const auto out = offset_outline({{0, 0}, {100, 0}, {100, 50}, {0, 50}}, p);
  EXPECT_NEAR(polygon_area(out), 104.0 * 54.0, 1e-3);
  p.distance = -30;
  EXPECT_THROW(offset_outline({{0, 0}, {100, 0}, {100, 50}, {0, 50}}, p), InvalidParameter);
}

TEST(Flatten, PlanarPatchWithStretchedParametersIsExact) {
  // The planar square 1000 x 1000 with x(u) = 400u + 600u^2: the (u,v) mesh is
  // distorted but the flattening of a plane must be the plane itself.
  const SurfaceFace face = test::stretched_plate();
  const FlatPatch f = flatten_patch(face, {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, FlattenParams{6});
  EXPECT_LT(f.strain_max, 1e-9);
  EXPECT_NEAR(f.area_3d, 1e6, 1e-3);
  ASSERT_EQ(f.outline.size(), 24u);
  ASSERT_EQ(f.corner_index.size(), 4u);
  for (int c = 0; c < 4; ++c) {
    const Vec2 a = f.outline[f.corner_index[c]], b = f.outline[f.corner_index[(c + 1) % 4]];
    EXPECT_NEAR((b - a).norm(), 1000.0, 1e-6);
  }
  EXPECT_NEAR(polygon_area(f.outline), 1e6, 1e-3);  // counter-clockwise
  FlattenParams bad;
  bad.subdivisions = 0;
  EXPECT_THROW(flatten_patch(face, {{0, 0}, {1, 0}, {1, 1}}, bad), InvalidParameter);
  std::vector<Vec2> many;  // 1000 corners x 64^2 pieces: refused, not attempted
  for (int k = 0; k < 1000; ++k)
    many.emplace_back(0.5 + 0.4 * std::cos(2 * kPi * k / 1000),
                      0.5 + 0.4 * std::sin(2 * kPi * k / 1000));
  EXPECT_THROW(flatten_patch(face, many, FlattenParams{64}), LimitExceeded);
}

TEST(Unfold, FlagsAnOutlineThatCrossesItself) {
  // A pentagon whose corner angles at the apex of its triangulation (every
  // triangulation of a pentagon is a fan) add up to more than 360 degrees in 3D
  // (a cone with excess angle): laid flat edge by edge it must overlap.
  std::vector<Vec2> uv;
  for (int k = 0; k < 5; ++k) uv.emplace_back(std::cos(2 * kPi * k / 5), std::sin(2 * kPi * k / 5));
  std::vector<Vec3> planar;
  for (const Vec2& p : uv) planar.emplace_back(500 * p.x(), 500 * p.y(), 0);
  const FlatPanel flat = unfold_panel(planar, uv);
  EXPECT_FALSE(flat.self_intersecting);
  ASSERT_EQ(flat.triangles.size(), 3u);
  int apex = -1;
  for (int v = 0; v < 5; ++v) {
    int in = 0;
    for (const auto& t : flat.triangles) in += (t[0] == v || t[1] == v || t[2] == v);
    if (in == 3) apex = v;
  }
  ASSERT_GE(apex, 0);
  std::vector<Vec3> xyz(5);
  xyz[apex] = Vec3(0, 0, 0);
  for (int k = 0; k < 4; ++k) {
    const double t = k * 150.0 * kPi / 180;
    xyz[(apex + 1 + k) % 5] = Vec3(1000 * std::cos(t), 1000 * std::sin(t), 100.0 * k);
  }
  EXPECT_TRUE(unfold_panel(xyz, uv).self_intersecting);
}
