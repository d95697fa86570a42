// The pipeline entry point (tessella/panelize.h) and the method declarations
// (tessella/methods.h): what Python runs, checked from C++.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>

#include "tessella/errors.h"
#include "tessella/grid_methods.h"
#include "tessella/panel_metrics.h"
#include "tessella/panelize.h"
#include "tessella/progress.h"
#include "test_faces.h"

namespace tessella {
namespace {

// The bundled doubly curved Bezier patch (examples/bezier_patch.brep).
std::shared_ptr<const SurfaceFace> bezier() {
  std::ifstream in(TESSELLA_EXAMPLES_DIR "/bezier_patch.brep");
  std::stringstream text;
  text << in.rdbuf();
  return std::make_shared<const SurfaceFace>(SurfaceFace::from_brep_string(text.str()));
}

TEST(Declarations, EveryMethodDeclaresItsParametersOnceWithRangesAndDefaults) {
  std::set<std::string> names;
  for (const MethodDeclaration& m : method_declarations()) {
    EXPECT_TRUE(names.insert(m.name).second) << m.name;
    EXPECT_FALSE(m.doc.empty());
    std::set<std::string> params;
    for (const ParamDeclaration& p : m.params) {
      EXPECT_TRUE(params.insert(p.name).second) << m.name << "." << p.name;
      EXPECT_FALSE(p.label.empty() || p.doc.empty() || p.property.empty()) << p.name;
      EXPECT_LE(p.minimum, p.maximum) << p.name;
    }
    for (const ParamDeclaration& s : shared_param_declarations())
      EXPECT_TRUE(params.count(s.name)) << m.name << " lacks " << s.name;
  }
  EXPECT_EQ(names.size(), 11u);
  // curvature_lines keeps its lines principal: its defaults differ from
  // boundary_driven's (no quadrangulation, smoothing or angle moves).
  const MethodDeclaration& cl = method_declaration("curvature_lines");
  EXPECT_EQ(std::get<bool>(cl.find("quadrangulate")->default_value), false);
  EXPECT_EQ(std::get<int>(cl.find("smoothing_iterations")->default_value), 0);
  EXPECT_EQ(
      std::get<bool>(method_declaration("boundary_driven").find("quadrangulate")->default_value),
      true);
  // Defaults come from the params structs themselves.
  const MethodDeclaration& iso = method_declaration("iso_grid");
  EXPECT_EQ(std::get<double>(iso.find("sliver_fraction")->default_value),
            GridClipParams{}.sliver_fraction);
  EXPECT_EQ(std::get<int>(iso.find("max_panels")->default_value), kDefaultMaxPanels);
  EXPECT_THROW(method_declaration("no_such_method"), InvalidParameter);
}

TEST(Pipeline, MatchesTheStagesRunOneByOne) {
  const auto face = bezier();
  const PanelizeResult r = panelize(face, "iso_grid", {{"u_count", 6}, {"v_count", 5}});
  // panelize evaluates in one FastEvaluation scope: so do the stages here.
  const SurfaceFace::FastEvaluation fast(*face);
  IsoGridParams p;
  p.u_count = 6;
  p.v_count = 5;
  const PanelMesh mesh = iso_grid(*face, p);
  ASSERT_EQ(r.mesh.panels, mesh.panels);
  const PanelMetrics m = measure_panels(*face, mesh);
  EXPECT_EQ(r.metrics.deviation, m.deviation);
  EXPECT_EQ(r.irregular, irregular_panels(mesh, m));
  EXPECT_EQ(r.summary.panel_count, 30);
  EXPECT_EQ(r.summary.quad_share, 1.0);
  EXPECT_EQ(r.summary.deviation.max, summarize(m.deviation).max);
  EXPECT_EQ(r.face.get(), face.get());  // the result keeps its face
  EXPECT_TRUE(r.fold_angle.empty());
}

TEST(Pipeline, ChecksValuesAgainstTheDeclarations) {
  const auto face = bezier();
  EXPECT_THROW(panelize(face, "iso_grid", {{"colour", 1}}), InvalidParameter);
  EXPECT_THROW(panelize(face, "iso_grid", {{"size", 100.0}, {"sliver_fraction", 2.0}}),
               InvalidParameter);
  EXPECT_THROW(panelize(face, "iso_grid", {{"u_count", 2.5}, {"v_count", 2}}), InvalidParameter);
  EXPECT_THROW(
      panelize(face, "walking_agent", {{"max_deviation", 1.0}, {"start", std::string("x")}}),
      InvalidParameter);
  try {
    panelize(face, "relaxed_grid", {{"weight", 3.0}});
    FAIL();
  } catch (const InvalidParameter& e) {
    EXPECT_NE(std::string(e.what()).find("weight"), std::string::npos) << e.what();
  }
}

TEST(Pipeline, FoldAnglesOfTheWalkingAgentAreTheTrianglesAngles) {
  const auto face = bezier();
  const PanelizeResult r =
      panelize(face, "walking_agent", {{"max_deviation", 0.002 * face->model_size()}});
  ASSERT_EQ(r.fold_angle.size(), r.mesh.folds.size());
  for (double a : r.fold_angle) EXPECT_TRUE(std::isnan(a) || (a >= 0.0 && a < 90.0)) << a;
}

TEST(Pipeline, CancelStopsEveryMethod) {
  const auto face = bezier();
  for (const MethodDeclaration& m : method_declarations()) {
    if (m.find("guides") != nullptr) continue;  // needs curves
    ParamValues v;
    if (m.find("size")) v["size"] = 0.05 * face->model_size();
    if (m.find("max_deviation")) v["max_deviation"] = 0.002 * face->model_size();
    ProgressScope scope([](double, const char*) { return false; });
    EXPECT_THROW(panelize(face, m.name, v), Cancelled) << m.name;
  }
}

}  // namespace
}  // namespace tessella
