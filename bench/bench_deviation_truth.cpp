// The deviation metric against an independent brute-force re-measure, on a
// surface that is the graph of its parameters (x = u, y = v: OCCT's terrain
// test face), where the distance from a point to the surface can be found
// without any projection of ours: every surface point of a 2 mm, then a
// 0.5 mm grid within reach of the point (the nearest point lies within the
// best distance found so far, horizontally too; samples beyond the
// surface's bounds clamped onto its border), then from the four nearest grid
// points at least 1 mm apart OCCT's local extremum search and a compass
// search clamped to the bounds (a nearest point on the border has no
// orthogonal foot). A panel's
// re-measure: its 25 x 25 grid (n + 1 x n + 1), then a compass search from
// its three farthest points down to a step of 1e-4 of the panel: a lower
// bound of the true maximum (the largest of exact distances), so a reported
// figure under it by more than 1% is an under-report for sure. And the
// brute-force distance at the metric's own top point (PanelDeviation::at):
// a reported figure over it is no distance of that point (a foot point on a
// wrong sheet). (A figure above the brute-force maximum but equal to the
// distance at its own top is a peak the brute force's grid stepped over.)
//
// Prints, for the border panels of iso_grid 72 x 72 and every 37th interior
// panel: the ratio reported / re-measured, how many lie below 0.99 (and how
// many of those the metric flags reliable: the trust defect) and above 1.01.
//   build/bench_deviation_truth [face.brep] [u_count] [n] [panel ...]
// (default /usr/share/opencascade/data/occ/terrain.brep, 72, n = 24, all
// border panels and every 37th interior one: about 6 minutes).
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <Geom_Surface.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "brute_force_distance.h"
#include "tessella/panel_metrics.h"
#include "tessella/panelize.h"
#include "tessella/surface_face.h"

using namespace tessella;

int main(int argc, char** argv) {
  const char* path = argc > 1 ? argv[1] : "/usr/share/opencascade/data/occ/terrain.brep";
  const int count = argc > 2 ? std::atoi(argv[2]) : 72;
  // Optional: a grid of n x n for the re-measure and only the panels listed.
  const int grid = argc > 3 ? std::atoi(argv[3]) : 24;
  std::vector<int> only;
  for (int a = 4; a < argc; ++a) only.push_back(std::atoi(argv[a]));
  TopoDS_Shape shape;
  BRep_Builder builder;
  if (!BRepTools::Read(shape, path, builder)) {
    std::fprintf(stderr, "cannot read %s\n", path);
    return 1;
  }
  TopoDS_Face face;
  double largest = -1;
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
    GProp_GProps props;
    BRepGProp::SurfaceProperties(ex.Current(), props);
    if (props.Mass() > largest) largest = props.Mass(), face = TopoDS::Face(ex.Current());
  }
  if (face.IsNull()) {
    std::fprintf(stderr, "%s has no face\n", path);
    return 1;
  }
  const auto sf = std::make_shared<const SurfaceFace>(SurfaceFace::from_occt_face(face));
  const Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
  // The re-measure needs x = u and y = v.
  const UvBounds b = sf->bounds();
  for (double a : {0.1, 0.5, 0.9})
    for (double c : {0.2, 0.7}) {
      const double u = b.u_min + a * (b.u_max - b.u_min), v = b.v_min + c * (b.v_max - b.v_min);
      const gp_Pnt q = surface->Value(u, v);
      if (std::abs(q.X() - u) + std::abs(q.Y() - v) > 1e-6 * sf->model_size()) {
        std::fprintf(stderr, "%s: not the graph of its parameters (x = u, y = v)\n", path);
        return 1;
      }
    }
  const auto t0 = std::chrono::steady_clock::now();
  const PanelizeResult r = panelize(sf, "iso_grid", {{"u_count", count}, {"v_count", count}});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::size_t np = r.mesh.panels.size();
  std::printf("%s: iso_grid %d x %d, %zu panels in %.2f s, %d flagged unreliable\n", path, count,
              count, np, seconds,
              int(std::count(r.metrics.deviation_unreliable.begin(),
                             r.metrics.deviation_unreliable.end(), 1)));
  if (np != std::size_t(count) * count) {
    std::fprintf(stderr, "expected %d x %d quads\n", count, count);
    return 1;
  }
  test::GraphDistance distance(surface);
  SurfaceFace::FastEvaluation fast(*sf);
  for (const bool border : {true, false}) {
    int checked = 0, below = 0, below_reliable = 0, above = 0, above_reliable = 0;
    double lo = 1e300, hi = 0, at_lo = 1e300, at_hi = 0;
    std::vector<std::array<double, 5>> rows;  // (ratio, panel, reported, re-measured, at top)
    int interior = 0;
    for (std::size_t k = 0; k < np; ++k) {
      const int i = int(k) / count, j = int(k) % count;
      const bool on_border = i == 0 || j == 0 || i == count - 1 || j == count - 1;
      if (on_border != border) continue;
      if (!border && interior++ % 37 != 0) continue;
      if (!only.empty() && std::find(only.begin(), only.end(), int(k)) == only.end()) continue;
      const auto& panel = r.mesh.panels[k];
      std::vector<Vec3> corners;
      std::vector<Vec2> uv;
      for (int v : panel) corners.push_back(r.mesh.xyz[v]), uv.push_back(r.mesh.uv[v]);
      const std::array<Vec3, 4> p{corners[0], corners[1], corners[2], corners[3]};
      const double reported = r.metrics.deviation[k];
      // The metric once more for its top point (the same figure, checked).
      const PanelDeviation again = measure_panel_deviation(*sf, corners, uv, {}, 8);
      if (again.value != reported) {
        std::fprintf(stderr, "panel %zu: measured %.17g, then %.17g\n", k, reported, again.value);
        return 1;
      }
      const double truth = test::dense_quad_maximum(distance, p, grid);
      // The true distance at the metric's own top: a figure above it is
      // not a distance of that point (a foot on a wrong sheet).
      const double at_top = distance(again.at);
      if (!only.empty()) {  // the panels asked for: their tops in detail
        const Projection g = sf->project(again.at);
        std::printf(
            "panel %zu: top (%.6f, %.6f, %.6f), reported %.6f, brute force there %.6f, "
            "the global search there %.6f\n",
            k, again.at.x(), again.at.y(), again.at.z(), reported, at_top, g.distance);
      }
      const bool unreliable = r.metrics.deviation_unreliable[k] != 0;
      const double ratio = reported / truth, over = reported / at_top;
      ++checked;
      lo = std::min(lo, ratio), hi = std::max(hi, ratio);
      at_lo = std::min(at_lo, over), at_hi = std::max(at_hi, over);
      if (ratio < 0.99) ++below, below_reliable += !unreliable;
      if (over > 1.01) ++above, above_reliable += !unreliable;
      rows.push_back({ratio, double(k), reported, truth, at_top});
    }
    if (checked == 0) continue;
    std::sort(rows.begin(), rows.end());
    std::printf(
        "%s panels: %d checked. Reported / brute-force maximum %.4f - %.4f, below 0.99: %d (%d "
        "flagged reliable). Reported / brute-force distance at the metric's top %.6f - %.6f, "
        "above 1.01: %d (%d flagged reliable)\n",
        border ? "border" : "interior (every 37th)", checked, lo, hi, below, below_reliable, at_lo,
        at_hi, above, above_reliable);
    for (std::size_t w = 0; w < std::min<std::size_t>(3, rows.size()); ++w)
      std::printf(
          "  lowest: panel %d reported %.4f, brute-force maximum %.4f, at its top %.4f (%s)\n",
          int(rows[w][1]), rows[w][2], rows[w][3], rows[w][4],
          r.metrics.deviation_unreliable[std::size_t(rows[w][1])] ? "unreliable" : "reliable");
  }
  return 0;
}
