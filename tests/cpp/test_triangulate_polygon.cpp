// triangulate_polygon (mesh/panel_model.h) against a plain reference: the
// textbook ear clipping that rescans every corner for every cut, followed by
// the same Lawson flips judged by summed atan2 angles. The core keeps ear
// states between cuts, decides most flips by a sine test and memoizes
// polygons: the triangles must be the same, index for index.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <vector>

#include "mesh/panel_model.h"

namespace tessella {
namespace {

using Tris = std::vector<std::array<int, 3>>;

double cross2(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

double angle_at(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 u = a - b, v = c - b;
  return std::atan2(std::abs(u.x() * v.y() - u.y() * v.x()), u.dot(v));
}

// Lawson flips with a std::map of directed edges (the last triangle of a
// repeated edge counts), an edge flipped when its opposite angles sum past pi.
void reference_delaunay(const std::vector<Vec2>& uv, Tris& tris) {
  for (int pass = 0; pass < 64; ++pass) {
    std::map<std::pair<int, int>, std::pair<int, int>> edge;
    for (int t = 0; t < int(tris.size()); ++t)
      for (int k = 0; k < 3; ++k) edge[{tris[t][k], tris[t][(k + 1) % 3]}] = {t, k};
    bool flipped = false;
    std::vector<char> touched(tris.size(), 0);
    for (const auto& [e, tk] : edge) {
      const auto other = edge.find({e.second, e.first});
      if (other == edge.end()) continue;
      const int t1 = tk.first, t2 = other->second.first;
      if (touched[t1] || touched[t2]) continue;
      const int a = e.first, b = e.second;
      const int c = tris[t1][(tk.second + 2) % 3];
      const int d = tris[t2][(other->second.second + 2) % 3];
      if (angle_at(uv[a], uv[c], uv[b]) + angle_at(uv[b], uv[d], uv[a]) <=
          3.14159265358979323846 + 1e-12)
        continue;
      const double sa = cross2(uv[c], uv[d], uv[a]), sb = cross2(uv[c], uv[d], uv[b]);
      if (!(sa * sb < 0)) continue;
      const bool ccw = cross2(uv[a], uv[b], uv[c]) > 0;
      tris[t1] = ccw ? std::array<int, 3>{c, a, d} : std::array<int, 3>{c, d, a};
      tris[t2] = ccw ? std::array<int, 3>{d, b, c} : std::array<int, 3>{d, c, b};
      touched[t1] = touched[t2] = 1;
      flipped = true;
    }
    if (!flipped) break;
  }
}

bool inside(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  return cross2(a, b, p) >= 0 && cross2(b, c, p) >= 0 && cross2(c, a, p) >= 0;
}

Tris reference(const std::vector<Vec2>& uv) {
  double area2 = 0;
  for (std::size_t i = 0; i < uv.size(); ++i)
    area2 += uv[i].x() * uv[(i + 1) % uv.size()].y() - uv[(i + 1) % uv.size()].x() * uv[i].y();
  if (area2 < 0) {
    std::vector<Vec2> mirrored;
    for (const Vec2& q : uv) mirrored.emplace_back(q.x(), -q.y());
    return reference(mirrored);
  }
  Tris tris;
  std::vector<int> ring(uv.size());
  std::iota(ring.begin(), ring.end(), 0);
  while (ring.size() > 3) {
    const std::size_t n = ring.size();
    std::size_t ear = n, best = 0;
    double best_turn = -INFINITY;
    for (std::size_t k = 0; k < n && ear == n; ++k) {
      const int ia = ring[(k + n - 1) % n], ib = ring[k], ic = ring[(k + 1) % n];
      const double turn = cross2(uv[ia], uv[ib], uv[ic]);
      if (turn > best_turn) best_turn = turn, best = k;
      if (turn <= 0) continue;
      bool empty = true;
      for (std::size_t m = 0; m < n && empty; ++m) {
        const int q = ring[m];
        if (q == ia || q == ib || q == ic) continue;
        if (uv[q] == uv[ia] || uv[q] == uv[ib] || uv[q] == uv[ic]) continue;
        if (inside(uv[q], uv[ia], uv[ib], uv[ic])) empty = false;
      }
      if (empty) ear = k;
    }
    if (ear == n) ear = best;
    tris.push_back({ring[(ear + n - 1) % n], ring[ear], ring[(ear + 1) % n]});
    ring.erase(ring.begin() + static_cast<long>(ear));
  }
  if (ring.size() == 3) tris.push_back({ring[0], ring[1], ring[2]});
  reference_delaunay(uv, tris);
  return tris;
}

// A star-shaped polygon with random radii; `runs` puts stretches of corners
// on straight lines (as a trim polyline crossing a cell), `flip` reverses it.
std::vector<Vec2> star(std::mt19937& rng, int n, bool runs, bool flip) {
  std::uniform_real_distribution<double> radius(0.3, 1.0), coin(0, 1);
  std::vector<Vec2> p;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    p.emplace_back(radius(rng) * std::cos(t), radius(rng) * std::sin(t));
  }
  if (runs) {
    for (int i = 1; i + 1 < n; i += 5) {
      if (coin(rng) < 0.5) continue;
      p[i] = 0.5 * (p[i - 1] + p[i + 1]);  // collinear with its neighbours
    }
  }
  if (flip) std::reverse(p.begin(), p.end());
  return p;
}

TEST(TriangulatePolygon, SameTrianglesAsTheReferenceEarClipping) {
  std::mt19937 rng(12345);
  int checked = 0;
  for (int n : {3, 4, 5, 6, 7, 8, 12, 20, 40, 90, 200}) {
    for (int trial = 0; trial < 30; ++trial) {
      const std::vector<Vec2> p = star(rng, n, trial % 3 == 1, trial % 2 == 1);
      const Tris expected = reference(p);
      ASSERT_EQ(triangulate_polygon(p), expected) << "n = " << n << ", trial " << trial;
      // Again: the second call is answered by the memo.
      ASSERT_EQ(triangulate_polygon(p), expected) << "n = " << n << ", trial " << trial;
      ASSERT_EQ(expected.size(), std::size_t(n - 2));
      ++checked;
    }
  }
  EXPECT_EQ(checked, 11 * 30);
}

TEST(TriangulatePolygon, CellCutByACurvedTrim) {
  // A square cell whose right side is a finely sampled arc (a boundary panel):
  // hundreds of nearly collinear corners, cut by thin ears and flipped.
  std::vector<Vec2> p{{0, 0}};
  for (int i = 0; i <= 300; ++i) {
    const double t = -0.5 + double(i) / 300;
    p.emplace_back(1 + 0.2 * std::cos(3 * t) - 0.2, t + 0.5);
  }
  p.emplace_back(0, 1);
  const Tris expected = reference(p);
  EXPECT_EQ(triangulate_polygon(p), expected);
  double area = 0;
  for (const auto& t : expected) area += 0.5 * cross2(p[t[0]], p[t[1]], p[t[2]]);
  double outline = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    outline += 0.5 * (p[i].x() * p[(i + 1) % p.size()].y() - p[(i + 1) % p.size()].x() * p[i].y());
  EXPECT_NEAR(area, outline, 1e-12);
}

TEST(TriangulatePolygon, CocircularAndRepeatedCorners) {
  // Corners on one circle (every flip a tie within rounding: a trim circle in
  // (u,v)), a circle with a notch, and outlines with repeated corners (ear
  // clipping then cuts degenerate ears and repeats directed edges): the flips
  // must still be those of the reference, index for index.
  std::vector<std::vector<Vec2>> cases;
  for (int n : {8, 24, 61}) {
    std::vector<Vec2> c;
    for (int i = 0; i < n; ++i)
      c.emplace_back(std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n));
    cases.push_back(c);
    c[n / 2] *= 0.4;
    cases.push_back(c);
    std::vector<Vec2> twice;
    for (int i = 0; i < n; ++i) {
      twice.push_back(c[i]);
      if (i % 5 == 0) twice.push_back(c[i]);
    }
    cases.push_back(twice);
  }
  for (std::size_t k = 0; k < cases.size(); ++k)
    ASSERT_EQ(triangulate_polygon(cases[k]), reference(cases[k])) << "case " << k;
}

}  // namespace
}  // namespace tessella
