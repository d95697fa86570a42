// Metrics on several threads (MetricsParams::threads): every panel's figures
// are the same bit for bit for any thread count, a failure or a cancel on any
// thread reaches the caller, and the global projection is counted.
#include <gtest/gtest.h>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepLib.hxx>
#include <Geom2d_Circle.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopoDS.hxx>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <gp_Ax2d.hxx>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "common/parallel_chunks.h"
#include "common/task_tree.h"
#include "mesh/boundary_pieces.h"
#include "tessella/grid_methods.h"
#include "tessella/panel_metrics.h"
#include "tessella/panelize.h"
#include "tessella/progress.h"
#include "test_faces.h"

namespace tessella {
namespace {

std::shared_ptr<const SurfaceFace> example(const std::string& name) {
  std::ifstream in(std::string(TESSELLA_EXAMPLES_DIR "/") + name + ".brep");
  std::stringstream text;
  text << in.rdbuf();
  return std::make_shared<const SurfaceFace>(SurfaceFace::from_brep_string(text.str()));
}

void expect_identical(const PanelMetrics& a, const PanelMetrics& b) {
  // EXPECT_EQ on vectors of doubles: exact, bit for bit (no NaN here).
  EXPECT_EQ(a.deviation, b.deviation);
  EXPECT_EQ(a.deviation_unreliable, b.deviation_unreliable);
  EXPECT_EQ(a.planarity, b.planarity);
  EXPECT_EQ(a.area, b.area);
  EXPECT_EQ(a.min_angle, b.min_angle);
  EXPECT_EQ(a.max_angle, b.max_angle);
  EXPECT_EQ(a.rod_length, b.rod_length);
}

TEST(MetricsThreads, OneAndTwoThreadsGiveIdenticalMetrics) {
  for (const char* name : {"trimmed_bspline_holes", "bezier_patch", "vault_openings"}) {
    SCOPED_TRACE(name);
    const auto face = example(name);
    IsoGridParams g;
    g.u_count = 23;  // boundary panels (n-gons) and quads, many chunks
    g.v_count = 19;
    const PanelMesh mesh = iso_grid(*face, g);
    ASSERT_GT(mesh.panels.size(), 100u);
    MetricsParams one, two;
    one.threads = 1;
    two.threads = 2;
    const PanelMetrics a = measure_panels(*face, mesh, one);
    const PanelMetrics b = measure_panels(*face, mesh, two);
    ASSERT_EQ(a.deviation.size(), mesh.panels.size());
    expect_identical(a, b);
    MetricsParams three = two;
    three.threads = 3;  // more threads than cores: still the same
    expect_identical(a, measure_panels(*face, mesh, three));
  }
}

TEST(MetricsThreads, ThePipelineIsIdenticalOnOneAndTwoThreads) {
  const auto face = example("trimmed_bspline_holes");
  // (coarser, its network overlaps an opening: refused by the coverage check)
  const ParamValues v{{"size", 0.04 * face->model_size()}};
  setenv("TESSELLA_THREADS", "1", 1);
  const PanelizeResult a = panelize(face, "boundary_driven", v);
  setenv("TESSELLA_THREADS", "2", 1);
  const PanelizeResult b = panelize(face, "boundary_driven", v);
  unsetenv("TESSELLA_THREADS");
  EXPECT_EQ(a.summary.metrics_threads, 1);
  EXPECT_EQ(b.summary.metrics_threads, 2);
  ASSERT_EQ(a.mesh.panels, b.mesh.panels);
  expect_identical(a.metrics, b.metrics);
  EXPECT_EQ(a.summary.global_projections, b.summary.global_projections);
}

TEST(MetricsThreads, WorkerThreadsFollowTheParameterThenTheEnvironment) {
  EXPECT_EQ(worker_threads(3), 3);
  setenv("TESSELLA_THREADS", "5", 1);
  EXPECT_EQ(worker_threads(0), 5);
  EXPECT_EQ(worker_threads(2), 2);
  unsetenv("TESSELLA_THREADS");
  EXPECT_GE(worker_threads(0), 1);
}

TEST(MetricsThreads, ABudgetCapsEveryLoopAndANestedLoopRunsOnOneThread) {
  setenv("TESSELLA_THREADS", "4", 1);
  {
    const ThreadBudget budget(2);
    EXPECT_EQ(worker_threads(0), 2);
    EXPECT_EQ(worker_threads(3), 2);  // even an explicit request
    {
      const ThreadBudget wider(8);  // a budget never widens the one around it
      EXPECT_EQ(worker_threads(0), 2);
    }
    // Inside a loop on two threads every worker's own loops get one thread;
    // a loop on one thread passes its caller's budget on.
    std::atomic<int> nested_max{0};
    ChunkQueue two(2, 1);
    run_chunks(two, 2, [&](bool) {
      std::size_t b = 0, e = 0;
      while (two.next(b, e)) nested_max = std::max(nested_max.load(), worker_threads(0));
    });
    EXPECT_EQ(nested_max.load(), 1);
    int inside_one = 0;
    ChunkQueue one(1, 1);
    run_chunks(one, 2, [&](bool) {
      std::size_t b = 0, e = 0;
      while (one.next(b, e)) inside_one = worker_threads(0);
    });
    EXPECT_EQ(inside_one, 2);
  }
  EXPECT_EQ(worker_threads(0), 4);  // the budget ends with its scope
  unsetenv("TESSELLA_THREADS");
}

TEST(MetricsThreads, EveryTaskOfATreeRunsOnceOnAnyNumberOfThreads) {
  // A binary tree of depth 12: every leaf is reached exactly once, whichever
  // thread takes which task.
  for (int threads : {1, 2, 3}) {
    SCOPED_TRACE(threads);
    std::vector<std::atomic<int>> visits(1 << 12);
    std::atomic<int> inner{0};
    run_task_tree(std::pair<int, int>{0, 0}, threads, [&](const auto& task, const auto& push) {
      const auto [depth, index] = task;
      if (depth == 12) {
        ++visits[std::size_t(index)];
        return;
      }
      ++inner;
      push(std::pair<int, int>{depth + 1, 2 * index});
      push(std::pair<int, int>{depth + 1, 2 * index + 1});
    });
    EXPECT_EQ(inner.load(), (1 << 12) - 1);
    for (const auto& v : visits) ASSERT_EQ(v.load(), 1);
  }
}

TEST(MetricsThreads, AFailingTaskOfATreeReachesTheCallerAndStopsTheOthers) {
  for (int threads : {1, 3}) {
    SCOPED_TRACE(threads);
    std::atomic<int> ran{0};
    EXPECT_THROW(run_task_tree(0, threads,
                               [&](const int& task, const auto& push) {
                                 ++ran;
                                 if (task == 50) throw std::runtime_error("task 50");
                                 if (task < 1000) push(task + 1), push(task + 1000);
                               }),
                 std::runtime_error);
    // Stopped soon after the failure, not run to the tree's end (1,000+).
    EXPECT_LT(ran.load(), 400);
  }
}

TEST(MetricsThreads, TheGridIsCutIdenticallyOnOneAndTwoThreads) {
  // clip_grid cuts the parts of its halving as tasks on every thread, and
  // in an evaluation scope (as panelize runs it) snaps the crossings onto
  // the trim curves on every thread too.
  for (const bool scoped : {false, true})
    for (const char* name : {"trimmed_bspline_holes", "vault_openings"}) {
      SCOPED_TRACE(name);
      SCOPED_TRACE(scoped ? "in a scope" : "no scope");
      const auto face = example(name);
      std::optional<SurfaceFace::FastEvaluation> fast;
      if (scoped) fast.emplace(*face);
      IsoGridParams g;
      g.u_count = 41;
      g.v_count = 37;
      PanelMesh a, b;
      {
        const ThreadBudget budget(1);
        a = iso_grid(*face, g);
      }
      {
        const ThreadBudget budget(2);
        b = iso_grid(*face, g);
      }
      ASSERT_GT(a.panels.size(), 500u);
      EXPECT_EQ(a.panels, b.panels);
      ASSERT_EQ(a.uv.size(), b.uv.size());
      for (std::size_t v = 0; v < a.uv.size(); ++v) {
        ASSERT_EQ(a.uv[v], b.uv[v]);
        ASSERT_EQ(a.xyz[v], b.xyz[v]);
      }
      EXPECT_EQ(a.is_node, b.is_node);
      EXPECT_EQ(a.rods, b.rods);
    }
}

// The boundary pieces are modelled panel by panel on every thread (in an
// evaluation scope, as panelize runs the stage): the same mesh, bend lines,
// new nodes and report as on one thread, with an allowance that makes the
// stage refine and split.
TEST(MetricsThreads, BoundaryPiecesAreModelledIdenticallyOnOneAndTwoThreads) {
  for (const char* name : {"trimmed_bspline_holes", "vault_openings"}) {
    SCOPED_TRACE(name);
    const auto face = example(name);
    const SurfaceFace::FastEvaluation fast(*face);
    IsoGridParams g;
    g.u_count = 23;
    g.v_count = 19;
    const PanelMesh mesh = iso_grid(*face, g);
    BoundaryPiecesParams bp;
    bp.max_deviation = 2e-4 * face->model_size();
    PanelMesh a = mesh, b = mesh;
    BoundaryPiecesReport ra, rb;
    {
      const ThreadBudget budget(1);
      ra = model_boundary_pieces(*face, a, bp);
    }
    {
      const ThreadBudget budget(2);
      rb = model_boundary_pieces(*face, b, bp);
    }
    EXPECT_GT(ra.modelled, 20);
    EXPECT_GT(ra.refined, 0);
    EXPECT_EQ(a.panels, b.panels);
    EXPECT_EQ(a.xyz, b.xyz);
    EXPECT_EQ(a.is_node, b.is_node);
    EXPECT_EQ(a.bends, b.bends);
    EXPECT_EQ(a.rods, b.rods);
    EXPECT_EQ(ra.origin, rb.origin);
    EXPECT_EQ(ra.changed, rb.changed);
    EXPECT_EQ(std::make_tuple(ra.modelled, ra.bends, ra.split, ra.refined),
              std::make_tuple(rb.modelled, rb.bends, rb.split, rb.refined));
    // The trim points moved onto their pieces' planes: the stage did its work.
    std::size_t moved = 0;
    for (std::size_t v = 0; v < mesh.xyz.size(); ++v) moved += a.xyz[v] != mesh.xyz[v] ? 1 : 0;
    EXPECT_GT(moved, 20u);
  }
}

// snap_to_trim on several threads at once (each call takes a set of the
// trim's projections of its own): every answer is the one a single thread
// gives, bit for bit, whatever thread asked and in whatever order.
TEST(MetricsThreads, TrimSnapsOnSeveralThreadsAtOnceAnswerAsOne) {
  const auto face = example("trimmed_bspline_holes");
  const std::vector<TrimLoop> loops = face->trim_loops(0.0002 * face->model_size());
  ASSERT_GE(loops.size(), 2u);
  // Chord midpoints of every loop (off the true trims by up to the deflection).
  std::vector<std::pair<int, Vec2>> asks;
  for (std::size_t k = 0; k < loops.size(); ++k)
    for (std::size_t i = 0; i < loops[k].uv.size(); ++i)
      asks.push_back({int(k), 0.5 * (loops[k].uv[i] + loops[k].uv[(i + 1) % loops[k].uv.size()])});
  ASSERT_GT(asks.size(), 100u);
  std::vector<Vec2> one;
  for (const auto& [loop, uv] : asks) one.push_back(face->snap_to_trim(loop, uv));
  std::size_t moved = 0;
  for (std::size_t i = 0; i < asks.size(); ++i) moved += one[i] != asks[i].second ? 1 : 0;
  EXPECT_GT(moved, asks.size() / 2);  // the chords' midpoints went onto the curves
  constexpr int kThreads = 4;
  std::vector<std::vector<Vec2>> got(kThreads, std::vector<Vec2>(asks.size()));
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] {
      // Each thread in its own order: t-th of every kThreads first, and so on.
      for (std::size_t r = 0; r < asks.size(); ++r) {
        const std::size_t i = (r * 7 + std::size_t(t) * 13) % asks.size();
        got[t][i] = face->snap_to_trim(asks[i].first, asks[i].second);
      }
    });
  for (std::thread& th : threads) th.join();
  for (int t = 0; t < kThreads; ++t)
    for (std::size_t i = 0; i < asks.size(); ++i) ASSERT_EQ(got[t][i], one[i]) << t << " " << i;
}

// A doubly curved bump of few spans (its curvature bounds come from spans
// subdivided for them) over 2 x 1.6 m, cut by a round opening: an outer loop
// of four edges and a hole. The methods whose stages now run on several
// threads (the trim cut's tasks, the coverage scans, walking_agent's merge
// checks) give the same panels, figures and coverage on one and two.
SurfaceFace bump_with_opening() {
  TColgp_Array2OfPnt poles(1, 5, 1, 5);
  for (int i = 1; i <= 5; ++i)
    for (int j = 1; j <= 5; ++j) {
      const double x = 500.0 * (i - 1), y = 400.0 * (j - 1);
      const double z = 300.0 * std::sin(0.7 * i) * std::cos(0.5 * j) + 40.0 * i * j;
      poles(i, j) = gp_Pnt(x, y, z);
    }
  TColStd_Array1OfReal knots(1, 3);
  TColStd_Array1OfInteger mults(1, 3);
  knots(1) = 0, knots(2) = 0.5, knots(3) = 1;
  mults(1) = mults(3) = 4, mults(2) = 1;
  const Handle(Geom_BSplineSurface) s =
      new Geom_BSplineSurface(poles, knots, knots, mults, mults, 3, 3);
  const TopoDS_Face face = BRepBuilderAPI_MakeFace(s, 1e-7).Face();
  // The opening: a circle in (u, v), turning against the outer loop.
  const Handle(Geom2d_Circle) circle =
      new Geom2d_Circle(gp_Ax2d(gp_Pnt2d(0.55, 0.5), gp_Dir2d(1, 0)), 0.17);
  TopoDS_Edge edge = BRepBuilderAPI_MakeEdge(circle, s).Edge();
  BRepLib::BuildCurves3d(edge);
  BRepBuilderAPI_MakeFace with_hole(face);
  with_hole.Add(TopoDS::Wire(BRepBuilderAPI_MakeWire(edge).Wire().Reversed()));
  return SurfaceFace::from_brep_string(test::brep(with_hole.Face()));
}

TEST(MetricsThreads, ACurvedFaceWithAnOpeningIsPanelizedIdenticallyOnOneAndTwoThreads) {
  const auto face = std::make_shared<const SurfaceFace>(bump_with_opening());
  ASSERT_EQ(face->trim_loops(0.01 * face->model_size()).size(), 2u);
  const double size = 0.05 * face->model_size();
  const std::vector<std::pair<std::string, ParamValues>> runs = {
      {"iso_grid", {{"size", size}}},
      {"walking_agent", {{"max_size", size}, {"max_deviation", 0.002 * face->model_size()}}}};
  for (const auto& [method, values] : runs) {
    SCOPED_TRACE(method);
    setenv("TESSELLA_THREADS", "1", 1);
    const PanelizeResult a = panelize(face, method, values);
    setenv("TESSELLA_THREADS", "2", 1);
    const PanelizeResult b = panelize(face, method, values);
    unsetenv("TESSELLA_THREADS");
    ASSERT_GT(a.mesh.panels.size(), 100u);
    ASSERT_EQ(a.mesh.panels, b.mesh.panels);
    ASSERT_EQ(a.mesh.xyz.size(), b.mesh.xyz.size());
    for (std::size_t v = 0; v < a.mesh.xyz.size(); ++v) ASSERT_EQ(a.mesh.xyz[v], b.mesh.xyz[v]);
    expect_identical(a.metrics, b.metrics);
    EXPECT_EQ(a.summary.gap_fraction, b.summary.gap_fraction);
    EXPECT_EQ(a.summary.overlap_fraction, b.summary.overlap_fraction);
    EXPECT_EQ(a.summary.model_area_ratio, b.summary.model_area_ratio);
    // And the coverage is real: the panels cover the face with the opening.
    EXPECT_LT(a.summary.gap_fraction, 1e-3);
    EXPECT_NEAR(a.summary.model_area_ratio, 1.0, 0.02);
  }
}

TEST(MetricsThreads, AFailureOnAnyThreadReachesTheCaller) {
  ChunkQueue queue(1000, 8);
  EXPECT_THROW(run_chunks(queue, 2,
                          [&](bool calling) {
                            std::size_t b, e;
                            while (queue.next(b, e))
                              if (!calling && b >= 80) throw std::runtime_error("worker");
                            if (!calling) throw std::runtime_error("worker");
                          }),
               std::runtime_error);
}

// The message of what run_chunks rethrows ("" if nothing).
std::string failure_of(ChunkQueue& queue, int threads, const std::function<void(bool)>& worker) {
  try {
    run_chunks(queue, threads, worker);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(MetricsThreads, TheLowestFailingChunkIsReportedWhateverTheTiming) {
  // Chunk 3 fails late, chunk 7 at once: on two threads chunk 7's failure
  // comes first in time, but a single thread meets chunk 3's first, and so
  // must every thread count (a face set's error names the same face).
  for (int threads : {1, 2, 3}) {
    ChunkQueue queue(10, 1);
    EXPECT_EQ(failure_of(queue, threads,
                         [&](bool) {
                           std::size_t b, e;
                           while (queue.next(b, e)) {
                             if (b == 3) {
                               std::this_thread::sleep_for(std::chrono::milliseconds(150));
                               throw std::runtime_error("chunk 3");
                             }
                             if (b == 7) throw std::runtime_error("chunk 7");
                           }
                         }),
              "chunk 3")
        << threads << " threads";
  }
  // A nested loop on a worker keeps its own claims: the outer failure is
  // still ranked by the outer chunk.
  ChunkQueue outer(6, 1);
  EXPECT_EQ(failure_of(outer, 2,
                       [&](bool) {
                         std::size_t b, e;
                         while (outer.next(b, e)) {
                           ChunkQueue inner(4, 1);
                           run_chunks(inner, 2, [&](bool) {
                             std::size_t ib, ie;
                             while (inner.next(ib, ie)) {
                             }
                           });
                           if (b == 1) {
                             std::this_thread::sleep_for(std::chrono::milliseconds(150));
                             throw std::runtime_error("outer 1");
                           }
                           if (b == 4) throw std::runtime_error("outer 4");
                         }
                       }),
            "outer 1");
}

TEST(MetricsThreads, CancelStopsTheParallelMetrics) {
  const auto face = example("trimmed_bspline_holes");
  IsoGridParams g;
  g.u_count = 30;
  g.v_count = 30;
  const PanelMesh mesh = iso_grid(*face, g);
  MetricsParams two;
  two.threads = 2;
  ProgressScope scope([](double, const char*) { return false; });
  EXPECT_THROW(measure_panels(*face, mesh, two), Cancelled);
}

TEST(MetricsThreads, GlobalProjectionsAreCountedAndAgreeWithAFreshSearch) {
  const auto face = example("bezier_patch");
  const UvBounds b = face->bounds();
  face->reset_global_projections();
  const Vec3 far = face->point(0.3 * (b.u_min + b.u_max), 0.5 * (b.v_min + b.v_max)) +
                   Vec3(0, 0, 0.3 * face->model_size());
  const Projection once = face->project(far);
  const Projection again = face->project(far);  // the reused search
  EXPECT_EQ(face->global_projections(), 2u);
  EXPECT_EQ(once.uv, again.uv);
  {
    const SurfaceFace::FastEvaluation fast(*face);  // the scope's own search
    const Projection scoped = face->project(far);
    EXPECT_NEAR((scoped.point - once.point).norm(), 0.0, 1e-9 * face->model_size());
  }
  EXPECT_EQ(face->global_projections(), 3u);
}

}  // namespace
}  // namespace tessella
