// Panel families on real panelizations: the bundled British Museum roof
// (iso_grid, about 5,500 panels at 1,050 mm) and a flat grid of identical
// panels, at several tolerances. Prints the time per grouping and the family
// count.
//   cmake --build build --target bench_families && build/bench_families
#include <benchmark/benchmark.h>

#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "tessella/grid_methods.h"
#include "tessella/panel_families.h"
#include "tessella/surface_face.h"

using namespace tessella;

namespace {

std::vector<std::vector<Vec3>> corners_of(const PanelMesh& mesh) {
  std::vector<std::vector<Vec3>> out;
  out.reserve(mesh.panels.size());
  for (const auto& p : mesh.panels) {
    std::vector<Vec3> c;
    for (int v : p) c.push_back(mesh.xyz[static_cast<std::size_t>(v)]);
    out.push_back(std::move(c));
  }
  return out;
}

// The roof panelized once (iso_grid, 1,050 mm).
const std::vector<std::vector<Vec3>>& roof_panels() {
  static const std::vector<std::vector<Vec3>> panels = [] {
    std::ifstream in(TESSELLA_EXAMPLES_DIR "/british_museum_roof.brep");
    std::stringstream text;
    text << in.rdbuf();
    const SurfaceFace face = SurfaceFace::from_brep_string(text.str());
    IsoGridParams p;
    p.size = 1050.0;
    return corners_of(iso_grid(face, p));
  }();
  return panels;
}

// 5,000 identical 1.5 m squares in a flat grid (every panel a twin).
const std::vector<std::vector<Vec3>>& flat_grid() {
  static const std::vector<std::vector<Vec3>> panels = [] {
    std::vector<std::vector<Vec3>> out;
    for (int i = 0; i < 100; ++i)
      for (int j = 0; j < 50; ++j) {
        const Vec3 o(1500.0 * i, 1500.0 * j, 0.0);
        out.push_back({o, o + Vec3(1500, 0, 0), o + Vec3(1500, 1500, 0), o + Vec3(0, 1500, 0)});
      }
    return out;
  }();
  return panels;
}

template <bool kRoof>
void BM_Families(benchmark::State& state) {
  const auto& panels = kRoof ? roof_panels() : flat_grid();
  PanelFamilyParams p;
  p.tolerance = static_cast<double>(state.range(0)) / 10.0;  // Arg in tenths of a mm
  int families = 0;
  double radius = 0.0;
  for (auto _ : state) {
    const PanelFamilies f = panel_families(panels, p);
    families = f.count();
    radius = f.twin_radius;
  }
  state.counters["panels"] = static_cast<double>(panels.size());
  state.counters["families"] = families;
  state.counters["twin_radius_mm"] = radius;
}

}  // namespace

// Tolerances 0.001 (rounded up to 0.1 here), 0.5, 2, 10 and 50 mm.
BENCHMARK_TEMPLATE(BM_Families, true)
    ->Name("families/british_museum_1050mm/tol_x10")
    ->Arg(1)
    ->Arg(5)
    ->Arg(20)
    ->Arg(100)
    ->Arg(500)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_Families, false)
    ->Name("families/flat_grid_5000/tol_x10")
    ->Arg(20)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
