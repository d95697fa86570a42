// Unfold and nesting throughput on the bundled trimmed B-spline example
// (equal_size_grid): panels per second.
//   build/bench_fabrication --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include <fstream>
#include <sstream>
#include <string>

#include "tessella/grid_methods.h"
#include "tessella/nest.h"
#include "tessella/surface_face.h"
#include "tessella/unfold.h"

using namespace tessella;

namespace {

PanelMesh example_mesh(double size) {
  std::ifstream in(TESSELLA_EXAMPLES_DIR "/trimmed_bspline_holes.brep");
  std::stringstream text;
  text << in.rdbuf();
  const SurfaceFace face = SurfaceFace::from_brep_string(text.str());
  EqualSizeGridParams p;
  p.size = size;
  return equal_size_grid(face, p);
}

void BM_Unfold(benchmark::State& state) {
  const PanelMesh mesh = example_mesh(static_cast<double>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(unfold_panels(mesh));
  state.counters["panels"] = static_cast<double>(mesh.panels.size());
  state.counters["panels/s"] = benchmark::Counter(
      static_cast<double>(mesh.panels.size() * state.iterations()), benchmark::Counter::kIsRate);
}

void BM_Nest(benchmark::State& state) {
  const PanelMesh mesh = example_mesh(static_cast<double>(state.range(0)));
  std::vector<std::vector<Vec2>> outlines;
  for (const FlatPanel& f : unfold_panels(mesh)) outlines.push_back(f.outline);
  NestParams p;
  p.sheet_width = 4000, p.sheet_height = 2500;
  NestLayout layout;
  for (auto _ : state) benchmark::DoNotOptimize(layout = nest_parts(outlines, p));
  state.counters["panels"] = static_cast<double>(outlines.size());
  state.counters["sheets"] = layout.sheet_count;
  state.counters["utilization"] = layout.utilization;
  state.counters["panels/s"] = benchmark::Counter(
      static_cast<double>(outlines.size() * state.iterations()), benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(BM_Unfold)->Arg(1500)->Arg(700)->Arg(400)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Nest)->Arg(1500)->Arg(700)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
