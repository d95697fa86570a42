// Panelizes the bundled trimmed B-spline example at several sizes and prints
// panels per second and the peak resident memory: the method alone, and the
// whole pipeline users run (tessella::panelize: method, metrics, folds, summary).
//   make bench            (or build/tessella_bench --benchmark_min_time=1)
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "tessella/grid_methods.h"
#include "tessella/panel_metrics.h"
#include "tessella/panelize.h"
#include "tessella/surface_face.h"

using namespace tessella;

namespace {

std::shared_ptr<const SurfaceFace> example_face_ptr() {
  static const std::shared_ptr<const SurfaceFace> face = [] {
    std::ifstream in(TESSELLA_EXAMPLES_DIR "/trimmed_bspline_holes.brep");
    std::stringstream text;
    text << in.rdbuf();
    return std::make_shared<const SurfaceFace>(SurfaceFace::from_brep_string(text.str()));
  }();
  return face;
}

const SurfaceFace& example_face() { return *example_face_ptr(); }

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // Linux reports KiB
}

// The pipeline entry point, as Python calls it.
template <bool kEqualSize>
void BM_Pipeline(benchmark::State& state) {
  const auto face = example_face_ptr();
  const ParamValues values{{"size", static_cast<double>(state.range(0))}};
  std::size_t panels = 0;
  for (auto _ : state) {
    const PanelizeResult r = panelize(face, kEqualSize ? "equal_size_grid" : "iso_grid", values);
    panels = r.mesh.panels.size();
  }
  state.counters["panels"] = static_cast<double>(panels);
  state.counters["panels_per_s"] = benchmark::Counter(
      static_cast<double>(panels) * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["peak_rss_MB"] = peak_rss_mb();
}

template <bool kEqualSize, bool kMeasure>
void BM_Panelize(benchmark::State& state) {
  const SurfaceFace& face = example_face();
  const double size = static_cast<double>(state.range(0));
  std::size_t panels = 0;
  for (auto _ : state) {
    PanelMesh mesh;
    if (kEqualSize) {
      EqualSizeGridParams p;
      p.size = size;
      mesh = equal_size_grid(face, p);
    } else {
      IsoGridParams p;
      p.size = size;
      mesh = iso_grid(face, p);
    }
    if (kMeasure) benchmark::DoNotOptimize(measure_panels(face, mesh));
    panels = mesh.panels.size();
  }
  state.counters["panels"] = static_cast<double>(panels);
  state.counters["panels_per_s"] = benchmark::Counter(
      static_cast<double>(panels) * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["peak_rss_MB"] = peak_rss_mb();
}

}  // namespace

BENCHMARK_TEMPLATE(BM_Panelize, false, false)
    ->Name("iso_grid/mesh")
    ->Arg(1000)
    ->Arg(500)
    ->Arg(250)
    ->Arg(125)
    ->Arg(60)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_Panelize, false, true)
    ->Name("iso_grid/mesh+metrics")
    ->Arg(1000)
    ->Arg(500)
    ->Arg(250)
    ->Arg(125)
    ->Arg(60)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_Panelize, true, true)
    ->Name("equal_size_grid/mesh+metrics")
    ->Arg(1000)
    ->Arg(500)
    ->Arg(250)
    ->Arg(125)
    ->Arg(60)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_Pipeline, false)
    ->Name("iso_grid/panelize")
    ->Arg(1000)
    ->Arg(250)
    ->Arg(60)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_Pipeline, true)
    ->Name("equal_size_grid/panelize")
    ->Arg(1000)
    ->Arg(250)
    ->Arg(60)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
