// Panel families: panel sets whose families are known by construction.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <cmath>
#include <limits>
#include <random>

#include "tessella/errors.h"
#include "tessella/panel_families.h"

using namespace tessella;

namespace {

using Panel = std::vector<Vec3>;

constexpr double kPi = 3.14159265358979323846;

// A rotation from three angles (radians).
Eigen::Matrix3d rotation(double a, double b, double c) {
  return (Eigen::AngleAxisd(a, Vec3::UnitZ()) * Eigen::AngleAxisd(b, Vec3::UnitY()) *
          Eigen::AngleAxisd(c, Vec3::UnitX()))
      .toRotationMatrix();
}

Panel moved(const Panel& p, const Eigen::Matrix3d& r, const Vec3& t) {
  Panel q;
  for (const Vec3& x : p) q.push_back(r * x + t);
  return q;
}

// The same panel listed from corner k.
Panel start_at(const Panel& p, std::size_t k) {
  Panel q;
  for (std::size_t i = 0; i < p.size(); ++i) q.push_back(p[(i + k) % p.size()]);
  return q;
}

// A flat square of side s in the xy plane.
Panel square(double s) { return {{0, 0, 0}, {s, 0, 0}, {s, s, 0}, {0, s, 0}}; }

// A bent quad with no symmetry (no mirror plane, no turn maps it onto itself).
Panel chiral() { return {{0, 0, 0}, {1000, 0, 0}, {1100, 800, 120}, {-50, 900, -60}}; }

// Mirror image through the yz plane (corner order kept).
Panel mirrored(const Panel& p) {
  Panel q;
  for (const Vec3& x : p) q.emplace_back(-x.x(), x.y(), x.z());
  return q;
}

// Independent lower bound of the distance of two panels under a given corner
// correspondence: half the largest change of a corner-to-corner distance.
double lower_bound(const Panel& a, const Panel& b) {
  double best = std::numeric_limits<double>::infinity();
  const std::size_t k = a.size();
  for (int rev = 0; rev < 2; ++rev)
    for (std::size_t s = 0; s < k; ++s) {
      double worst = 0.0;
      for (std::size_t i = 0; i < k; ++i)
        for (std::size_t j = 0; j < k; ++j) {
          const std::size_t bi = rev ? (s + k - i) % k : (i + s) % k;
          const std::size_t bj = rev ? (s + k - j) % k : (j + s) % k;
          worst = std::max(worst, std::abs((a[i] - a[j]).norm() - (b[bi] - b[bj]).norm()) / 2);
        }
      best = std::min(best, worst);
    }
  return best;
}

// Brute force: least, over every correspondence, of the largest corner
// distance after the least-squares alignment (no pruning at all).
double brute_distance(const Panel& a, const Panel& b, bool mirror) {
  const std::size_t k = a.size();
  Vec3 ca = Vec3::Zero(), cb = Vec3::Zero();
  for (std::size_t i = 0; i < k; ++i) ca += a[i] / k, cb += b[i] / k;
  double best = std::numeric_limits<double>::infinity();
  for (int rev = 0; rev <= (mirror ? 1 : 0); ++rev)
    for (std::size_t s = 0; s < k; ++s) {
      Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
      std::vector<Vec3> pa, pb;
      for (std::size_t i = 0; i < k; ++i) {
        pa.push_back(a[i] - ca);
        pb.push_back(b[rev ? (s + k - i) % k : (i + s) % k] - cb);
        h += pb.back() * pa.back().transpose();
      }
      Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
      Eigen::Matrix3d v = svd.matrixV();
      if (!mirror && (v * svd.matrixU().transpose()).determinant() < 0) v.col(2) *= -1;
      const Eigen::Matrix3d r = v * svd.matrixU().transpose();
      double worst = 0;
      for (std::size_t i = 0; i < k; ++i) worst = std::max(worst, (r * pb[i] - pa[i]).norm());
      best = std::min(best, worst);
    }
  return best;
}

}  // namespace

TEST(PanelFamilies, DistanceEqualsTheBruteForceAlignment) {
  // The pruning (corner-distance changes, the RMS bound from the key matrix)
  // never changes the distance: random bent quads and pentagons, near and far.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coord(-1000, 1000), push(-30, 30);
  for (int trial = 0; trial < 300; ++trial) {
    const std::size_t k = 4 + trial % 2;
    Panel a, b;
    for (std::size_t i = 0; i < k; ++i) a.emplace_back(coord(rng), coord(rng), 0.2 * coord(rng));
    for (const Vec3& x : a) b.push_back(x + Vec3(push(rng), push(rng), push(rng)) * (trial % 3));
    if (trial % 5 == 0) b = start_at(b, 1);
    if (trial % 7 == 0) b = mirrored(b);
    b = moved(b, rotation(0.1 * trial, 1.0, -0.3 * trial), Vec3(trial, -2.0 * trial, 5));
    for (bool mirror : {true, false})
      EXPECT_NEAR(panel_distance(a, b, mirror), brute_distance(a, b, mirror), 1e-9)
          << "trial " << trial << " mirror " << mirror;
  }
}

TEST(PanelFamilies, MovedCopiesOfTemplatesClusterIntoExactlyThoseTemplates) {
  // Four templates that differ by far more than the tolerance; 40 copies each,
  // turned, moved, listed from another corner and with every corner pushed by
  // up to 0.4 mm (so every pair within a group is within 2 mm, while groups
  // are hundreds of mm apart).
  const std::vector<Panel> templates = {chiral(),
                                        square(1500),
                                        {{0, 0, 0}, {1400, 0, 0}, {1300, 1200, 50}, {100, 1250, 0}},
                                        {{0, 0, 0}, {1500, 0, 0}, {700, 1300, 0}}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-kPi, kPi), shift(-2e4, 2e4), push(-0.23, 0.23);
  std::vector<Panel> panels;
  std::vector<int> group;
  for (int copy = 0; copy < 40; ++copy)
    for (std::size_t t = 0; t < templates.size(); ++t) {
      Panel p = templates[t];
      for (Vec3& x : p) x += Vec3(push(rng), push(rng), push(rng));
      p = moved(start_at(p, copy % p.size()), rotation(angle(rng), angle(rng), angle(rng)),
                Vec3(shift(rng), shift(rng), shift(rng)));
      panels.push_back(p);
      group.push_back(static_cast<int>(t));
    }
  const PanelFamilies f = panel_families(panels, {2.0, false});
  ASSERT_EQ(f.count(), 4);
  ASSERT_EQ(f.labels.size(), panels.size());
  // Families numbered by lowest panel: panel t of the first copy is family t.
  for (std::size_t p = 0; p < panels.size(); ++p) {
    EXPECT_EQ(f.labels[p], group[p]) << "panel " << p;
    EXPECT_LE(f.error[p], 2.0);
    EXPECT_GE(f.error[p] + 1e-9, lower_bound(panels[f.templates[f.labels[p]]], panels[p]));
    EXPECT_LE(f.error[p], f.max_error[f.labels[p]]);
  }
  for (int t = 0; t < 4; ++t) EXPECT_EQ(f.labels[f.templates[t]], t);
}

TEST(PanelFamilies, ExactCopiesHaveNoError) {
  std::vector<Panel> panels;
  for (int i = 0; i < 500; ++i)
    panels.push_back(
        moved(chiral(), rotation(0.01 * i, 0.02 * i, -0.03 * i), Vec3(3000.0 * i, 0, 0)));
  const PanelFamilies f = panel_families(panels, {});
  ASSERT_EQ(f.count(), 1);
  EXPECT_EQ(f.templates[0], 0);
  for (double e : f.error) EXPECT_LT(e, 1e-6);
}

TEST(PanelFamilies, MirrorImagesShareAFamilyOnlyWithMirror) {
  const std::vector<Panel> panels = {chiral(), mirrored(chiral()),
                                     moved(mirrored(chiral()), rotation(1, 2, 3), Vec3(5, 6, 7))};
  EXPECT_EQ(panel_families(panels, {2.0, true}).labels, (std::vector<int>{0, 0, 0}));
  EXPECT_EQ(panel_families(panels, {2.0, false}).labels, (std::vector<int>{0, 1, 1}));
  EXPECT_GT(panel_distance(panels[0], panels[1], false), 50.0);
  EXPECT_LT(panel_distance(panels[0], panels[1], true), 1e-6);
}

TEST(PanelFamilies, GreedyCoverPicksThePanelBetweenTwoFarApart) {
  // Squares of side 100, 105 and 102.5: centred squares whose sides differ by
  // d are sqrt(2)/2 d apart at the corners, so 102.5 is within 2 mm of both
  // others (1.77) while they are 3.54 apart: one family, 102.5 its template
  // (a first-come grouping would make two).
  const std::vector<Panel> panels = {square(100), square(105), square(102.5)};
  const PanelFamilies f = panel_families(panels, {2.0, true});
  EXPECT_EQ(f.labels, (std::vector<int>{0, 0, 0}));
  EXPECT_EQ(f.templates, (std::vector<int>{2}));
  EXPECT_NEAR(f.max_error[0], 2.5 * std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(f.error[0], 2.5 * std::sqrt(0.5), 1e-9);
  EXPECT_EQ(f.error[2], 0.0);
  // At 1.5 mm nothing is within reach of anything else.
  EXPECT_EQ(panel_families(panels, {1.5, true}).count(), 3);
}

TEST(PanelFamilies, TemplateMinimisesTheWorstDeviation) {
  // Sides 100 .. 101.2 in steps of 0.3 mm, tolerance 1 mm: 100 covers the
  // panels up to 101.2 (0.85 mm); the best template is the middle one
  // (100.6: 0.42 mm to either end).
  std::vector<Panel> panels;
  for (int i = 0; i <= 4; ++i) panels.push_back(square(100.0 + 0.3 * i));
  const PanelFamilies f = panel_families(panels, {1.0, true});
  ASSERT_EQ(f.count(), 1);
  EXPECT_EQ(f.templates[0], 2);
  EXPECT_NEAR(f.max_error[0], 0.6 * std::sqrt(0.5), 1e-9);
}

TEST(PanelFamilies, RowsOfASurfaceOfRevolutionAreTheFamilies) {
  // A dome r(z) = 10000 cos(phi), panelled along 24 meridians and 8
  // parallels: the panels of one row are turned copies of each other, rows
  // differ by far more than the tolerance.
  const int meridians = 24, rows = 8;
  auto node = [&](int i, int j) {
    const double phi = 0.1 + 1.2 * j / rows, theta = 2 * kPi * i / meridians;
    return Vec3(10000 * std::cos(phi) * std::cos(theta), 10000 * std::cos(phi) * std::sin(theta),
                10000 * std::sin(phi));
  };
  std::vector<Panel> panels;
  std::vector<int> row;
  for (int i = 0; i < meridians; ++i)  // meridian by meridian: rows interleave
    for (int j = 0; j < rows; ++j) {
      panels.push_back({node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)});
      row.push_back(j);
    }
  for (bool mirror : {true, false}) {
    const PanelFamilies f = panel_families(panels, {2.0, mirror});
    ASSERT_EQ(f.count(), rows);
    for (std::size_t p = 0; p < panels.size(); ++p) {
      EXPECT_EQ(f.labels[p], row[p]);
      EXPECT_LT(f.error[p], 1e-6);
    }
  }
}

TEST(PanelFamilies, CornerCountsNeverMix) {
  const Panel tri = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const Panel quad = {{0, 0, 0}, {1, 0, 0}, {1, 1e-3, 0}, {0, 1, 0}};
  const PanelFamilies f = panel_families({tri, quad, tri}, {100.0, true});
  EXPECT_EQ(f.labels, (std::vector<int>{0, 1, 0}));
  EXPECT_TRUE(std::isinf(panel_distance(tri, quad, true)));
}

TEST(PanelFamilies, Deterministic) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> noise(-3, 3);
  std::vector<Panel> panels;
  for (int i = 0; i < 600; ++i) {
    Panel p = square(1500);
    for (Vec3& x : p) x += Vec3(noise(rng), noise(rng), noise(rng));
    panels.push_back(moved(p, rotation(0.1 * i, 0.2, 0.3 * i), Vec3(i, 2 * i, 3 * i)));
  }
  const PanelFamilies a = panel_families(panels, {5.0, true});
  const PanelFamilies b = panel_families(panels, {5.0, true});
  EXPECT_EQ(a.labels, b.labels);
  EXPECT_EQ(a.templates, b.templates);
  EXPECT_EQ(a.error, b.error);  // bit for bit
  EXPECT_EQ(a.max_error, b.max_error);
  EXPECT_LT(a.count(), 600);
  for (std::size_t p = 0; p < panels.size(); ++p) EXPECT_LE(a.error[p], 5.0);
}

TEST(PanelFamilies, CoarseGroupingKeepsTheToleranceAndRoughlyTheCount) {
  // Slightly different squares (side 1500 +- 4 mm, noise 0.5 mm): at 5 mm
  // nearly every pair is within reach. A tiny pair budget forces the coarse
  // grouping (a larger twin radius); every panel stays within the tolerance.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> side(-4, 4), noise(-0.5, 0.5);
  std::vector<Panel> panels;
  for (int i = 0; i < 400; ++i) {
    const double s = 1500 + side(rng);
    Panel p = {{0, 0, 0}, {s, 0, 0}, {s, s + side(rng), 0}, {0, s, 0}};
    for (Vec3& x : p) x += Vec3(noise(rng), noise(rng), noise(rng));
    panels.push_back(moved(p, rotation(0.3 * i, 0.1, 0.7 * i), Vec3(5.0 * i, 0, 0)));
  }
  PanelFamilyParams full{5.0, true};
  PanelFamilyParams coarse{5.0, true, 10};
  const PanelFamilies a = panel_families(panels, full);
  const PanelFamilies b = panel_families(panels, coarse);
  EXPECT_DOUBLE_EQ(a.twin_radius, 5e-3);
  EXPECT_GT(b.twin_radius, 5e-3);
  EXPECT_LE(a.count(), b.count());
  EXPECT_LE(b.count(), 3 * a.count());
  for (const PanelFamilies* f : {&a, &b})
    for (std::size_t p = 0; p < panels.size(); ++p) {
      EXPECT_LE(f->error[p], 5.0);
      EXPECT_GE(f->error[p] + 1e-9, lower_bound(panels[f->templates[f->labels[p]]], panels[p]));
    }
}

TEST(PanelFamilies, EmptyInputGivesNoFamilies) {
  const PanelFamilies f = panel_families({}, {});
  EXPECT_EQ(f.count(), 0);
  EXPECT_TRUE(f.labels.empty());
}

TEST(PanelFamilies, RejectsBadParametersAndPanels) {
  const std::vector<Panel> ok = {square(1)};
  for (double tol : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity(), 2e9}) {
    try {
      panel_families(ok, {tol, true});
      FAIL() << "tolerance " << tol << " accepted";
    } catch (const InvalidParameter& e) {
      EXPECT_NE(std::string(e.what()).find("family_tolerance"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(panel_families(ok, {2.0, true, -1}), InvalidParameter);
  EXPECT_THROW(panel_families({square(1), {{0, 0, 0}, {1, 0, 0}}}, {}), InvalidGeometry);
  EXPECT_THROW(panel_families({{{0, 0, 0}, {1, 0, 0}, {0, std::nan(""), 0}}}, {}), InvalidGeometry);
}
