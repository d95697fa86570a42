// Core time of walking_agent (the method call alone, no metrics, no document)
// for about 2000 panels, and of its rivals on the same face.
//   build/bench_walking_agent            (target: ~2000 panels in < 50 ms)
// Faces: a doubly curved 20 x 20 m Bezier patch (untrimmed), and the bundled
// trimmed B-spline example with holes.
#include <benchmark/benchmark.h>

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepTools.hxx>
#include <Geom_BezierSurface.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <fstream>
#include <sstream>
#include <string>

#include "tessella/relaxed_grid.h"
#include "tessella/surface_face.h"
#include "tessella/walking_agent.h"

using namespace tessella;

namespace {

// 20 x 20 m, a dome (2 m rise) with a saddle-like twist towards one corner.
const SurfaceFace& dome() {
  static const SurfaceFace face = [] {
    TColgp_Array2OfPnt poles(1, 4, 1, 4);
    const double z[4][4] = {
        {0, 800, 900, 0}, {700, 2600, 2400, 600}, {600, 2500, 3200, 1400}, {0, 900, 1800, 2200}};
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        poles(i + 1, j + 1) = gp_Pnt(i * 20000.0 / 3, j * 20000.0 / 3, z[i][j]);
    Handle(Geom_BezierSurface) s = new Geom_BezierSurface(poles);
    std::ostringstream out;
    const TopoDS_Shape shape = BRepBuilderAPI_MakeFace(s, 1e-7).Face();
    BRepTools::Write(shape, out);
    return SurfaceFace::from_brep_string(out.str());
  }();
  return face;
}

const SurfaceFace& trimmed() {
  static const SurfaceFace face = [] {
    std::ifstream in(TESSELLA_EXAMPLES_DIR "/trimmed_bspline_holes.brep");
    std::stringstream text;
    text << in.rdbuf();
    return SurfaceFace::from_brep_string(text.str());
  }();
  return face;
}

template <const SurfaceFace& (*Face)()>
void BM_WalkingAgent(benchmark::State& state) {
  const SurfaceFace& face = Face();
  WalkingAgentParams p;
  p.max_deviation = static_cast<double>(state.range(0)) / 10.0;  // arg: bound in 0.1 mm
  p.edge_share = static_cast<double>(state.range(1)) / 10.0;     // 0 = automatic
  std::size_t panels = 0;
  face.reset_evaluations();
  for (auto _ : state) {
    const PanelMesh mesh = walking_agent(face, p);
    panels = mesh.panels.size();
  }
  state.counters["panels"] = static_cast<double>(panels);
  state.counters["evals_per_call"] =
      static_cast<double>(face.evaluations()) / static_cast<double>(state.iterations());
}

template <const SurfaceFace& (*Face)()>
void BM_GradientDescent(benchmark::State& state) {
  const SurfaceFace& face = Face();
  GradientDescentParams p;
  p.max_deviation = static_cast<double>(state.range(0)) / 10.0;
  std::size_t panels = 0;
  for (auto _ : state) panels = gradient_descent(face, p).panels.size();
  state.counters["panels"] = static_cast<double>(panels);
}

void BM_RelaxedGrid(benchmark::State& state) {
  RelaxedGridParams p;
  p.u_count = p.v_count = static_cast<int>(state.range(0));
  std::size_t panels = 0;
  for (auto _ : state) panels = relaxed_grid(dome(), p).panels.size();
  state.counters["panels"] = static_cast<double>(panels);
}

}  // namespace

// Args: bound (0.1 mm), edge share (0.1; 0 = try 1, 0.7, 0.5).
BENCHMARK_TEMPLATE(BM_WalkingAgent, dome)
    ->Name("walking_agent/dome")
    ->Args({100, 10})
    ->Args({30, 10})
    ->Args({30, 0})
    ->Args({20, 10})
    ->Args({20, 0})
    ->Args({15, 10})
    ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_WalkingAgent, trimmed)
    ->Name("walking_agent/trimmed_holes")
    ->Args({100, 10})
    ->Args({20, 10})
    ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_GradientDescent, dome)
    ->Name("gradient_descent/dome")
    ->Arg(30)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RelaxedGrid)->Name("relaxed_grid/dome")->Arg(45)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
