// Face sets (tessella/face_set.h): faces of one sewn shell panelized together
// agree along their shared edges; the result does not depend on the threads.
#include <gtest/gtest.h>

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRep_Builder.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopoDS_Compound.hxx>
#include <cmath>
#include <map>
#include <set>

#include "faceset/shared_edge_check.h"
#include "tessella/errors.h"
#include "tessella/face_set.h"
#include "test_faces.h"

namespace tessella {
namespace {

// A bicubic Bezier-like patch.
Handle(Geom_BSplineSurface) patch() {
  TColgp_Array2OfPnt poles(1, 4, 1, 4);
  for (int i = 1; i <= 4; ++i)
    for (int j = 1; j <= 4; ++j)
      poles(i, j) = gp_Pnt(3000.0 * i, 2500.0 * j, 700.0 * std::sin(1.3 * i) * std::cos(0.9 * j));
  TColStd_Array1OfReal knots(1, 2);
  knots(1) = 0, knots(2) = 1;
  TColStd_Array1OfInteger mults(1, 2);
  mults(1) = mults(2) = 4;
  return new Geom_BSplineSurface(poles, knots, knots, mults, mults, 3, 3);
}

// The patch cut at u = 0.4 into two faces, sewn.
std::string split_patch() {
  const Handle(Geom_BSplineSurface) s = patch();
  BRepBuilderAPI_Sewing sewing;
  sewing.Add(BRepBuilderAPI_MakeFace(s, 0.0, 0.4, 0.0, 1.0, 1e-7).Face());
  sewing.Add(BRepBuilderAPI_MakeFace(s, 0.4, 1.0, 0.0, 1.0, 1e-7).Face());
  sewing.Perform();
  return test::brep(sewing.SewedShape());
}

// The same two faces built apart (a compound: the cut is two edges), the
// second lifted by `lift` mm.
std::string unsewn_patch(double lift) {
  const Handle(Geom_BSplineSurface) s = patch();
  Handle(Geom_BSplineSurface) t = Handle(Geom_BSplineSurface)::DownCast(s->Copy());
  t->Translate(gp_Vec(0, 0, lift));
  TopoDS_Compound c;
  BRep_Builder b;
  b.MakeCompound(c);
  b.Add(c, BRepBuilderAPI_MakeFace(s, 0.0, 0.4, 0.0, 1.0, 1e-7).Face());
  b.Add(c, BRepBuilderAPI_MakeFace(t, 0.4, 1.0, 0.0, 1.0, 1e-7).Face());
  return test::brep(c);
}

// Panel sides (vertex pairs) with the faces of the panels along them.
std::map<std::pair<int, int>, std::multiset<int>> sides(const FaceSetResult& r) {
  std::map<std::pair<int, int>, std::multiset<int>> out;
  const auto& panels = r.combined.mesh.panels;
  for (std::size_t p = 0; p < panels.size(); ++p)
    for (std::size_t i = 0; i < panels[p].size(); ++i) {
      const int a = panels[p][i], b = panels[p][(i + 1) % panels[p].size()];
      out[{std::min(a, b), std::max(a, b)}].insert(r.panel_face[p]);
    }
  return out;
}

TEST(FaceSet, SharedEdgeHasOneNodeAtEachPositionAndPanelsOnBothSides) {
  const FaceSet set = FaceSet::from_brep_string(split_patch());
  ASSERT_EQ(set.size(), 2u);
  ASSERT_EQ(set.shared_edge_count(), 1u);
  const FaceSetResult r = panelize_faces(set, "equal_size_grid", {{"size", 900.0}});
  const PanelMesh& m = r.combined.mesh;
  // No two nodes at one position.
  const double tol = 1e-6 * r.combined.summary.model_size;
  for (std::size_t a = 0; a < m.xyz.size(); ++a)
    for (std::size_t b = a + 1; b < m.xyz.size(); ++b)
      ASSERT_GT((m.xyz[a] - m.xyz[b]).norm(), tol) << a << " " << b;
  // The split line is x-independent in (u): its nodes are the vertices both
  // faces use; every side between two of them bounds one panel of each face.
  std::set<int> both;
  std::map<int, std::set<int>> faces_of_vertex;
  for (std::size_t p = 0; p < m.panels.size(); ++p)
    for (int v : m.panels[p]) faces_of_vertex[v].insert(r.panel_face[p]);
  for (const auto& [v, f] : faces_of_vertex)
    if (f.size() == 2) both.insert(v);
  ASSERT_GE(both.size(), 5u);
  int shared_sides = 0;
  for (const auto& [side, faces] : sides(r)) {
    if (!both.count(side.first) || !both.count(side.second)) continue;
    if (faces.size() == 1 && faces.count(0) + faces.count(1) == 1) continue;  // a free border
    EXPECT_EQ(faces, (std::multiset<int>{0, 1}));
    ++shared_sides;
  }
  EXPECT_EQ(shared_sides, static_cast<int>(both.size()) - 1);  // an open edge, node to node
  EXPECT_EQ(r.shared_edge_nodes, static_cast<int>(both.size()));
  EXPECT_GT(r.shared_nodes_taken_over, 0);  // arc-length spacing differs on the two faces
  // One rod per side along it.
  std::set<std::pair<int, int>> rods;
  for (const auto& rod : m.rods) EXPECT_TRUE(rods.insert({rod[0], rod[1]}).second);
}

TEST(FaceSet, TheCheckOfTheSharedEdgesFindsAGapAndATJunction) {
  const FaceSet set = FaceSet::from_brep_string(split_patch());
  const FaceSetResult r = panelize_faces(set, "equal_size_grid", {{"size", 900.0}});
  // The vertices both faces use lie on the split: one segment fewer than them.
  std::map<int, std::set<int>> faces_of_vertex;
  const PanelMesh& m = r.combined.mesh;
  for (std::size_t p = 0; p < m.panels.size(); ++p)
    for (int v : m.panels[p]) faces_of_vertex[v].insert(r.panel_face[p]);
  int both = 0;
  for (const auto& [v, f] : faces_of_vertex) both += f.size() == 2 ? 1 : 0;
  EXPECT_EQ(r.shared_edge_segments, both - 1);
  EXPECT_EQ(r.unmatched_shared_segments, 0);
  EXPECT_EQ(r.join_warning, "");

  // A gap: face 1's panels along the split taken away.
  PanelMesh gap = m;
  gap.panels.clear();
  std::vector<int> gap_face;
  int removed = 0;
  for (std::size_t p = 0; p < m.panels.size(); ++p) {
    int on_split = 0;
    for (int v : m.panels[p]) on_split += faces_of_vertex[v].size() == 2 ? 1 : 0;
    if (r.panel_face[p] == 1 && on_split >= 2) {
      ++removed;
      continue;
    }
    gap.panels.push_back(m.panels[p]);
    gap_face.push_back(r.panel_face[p]);
  }
  ASSERT_GT(removed, 0);
  const SharedEdgeCheck g = check_shared_edges(set.impl(), gap, gap_face);
  EXPECT_EQ(g.segments, both - 1);
  EXPECT_EQ(g.unmatched, both - 1);  // each of them had a panel of face 1
  EXPECT_EQ(g.first_faces, (std::array<int, 2>{0, 1}));

  // A T-junction: a node of face 0's in the middle of one segment, face 1's
  // panel still running past it.
  PanelMesh t = m;
  bool done = false;
  for (std::size_t p = 0; p < t.panels.size() && !done; ++p) {
    if (r.panel_face[p] != 0) continue;
    std::vector<int>& q = t.panels[p];
    for (std::size_t i = 0; i < q.size() && !done; ++i) {
      const int a = q[i], b = q[(i + 1) % q.size()];
      if (faces_of_vertex[a].size() != 2 || faces_of_vertex[b].size() != 2) continue;
      // The split's point halfway, on the surface (the split is u = 0.4).
      const Vec2 uv = 0.5 * (m.uv[static_cast<std::size_t>(a)] + m.uv[static_cast<std::size_t>(b)]);
      t.uv.push_back(uv);
      t.xyz.push_back(set.face(0)->point(uv.x(), uv.y()));
      t.is_node.push_back(1);
      q.insert(q.begin() + static_cast<long>(i + 1), static_cast<int>(t.xyz.size()) - 1);
      done = true;
    }
  }
  ASSERT_TRUE(done);
  const SharedEdgeCheck c = check_shared_edges(set.impl(), t, r.panel_face);
  EXPECT_EQ(c.segments, both);  // the new node splits one segment in two
  EXPECT_EQ(c.unmatched, 2);    // face 1 runs along neither half
  EXPECT_LT((c.first_at - t.xyz.back()).norm(), 0.5 * 900.0);
}

TEST(FaceSet, SameResultOnOneAndTwoThreads) {
  const FaceSet set = FaceSet::from_brep_string(split_patch());
  const FaceSetResult one = panelize_faces(set, "iso_grid", {{"size", 800.0}}, 1);
  const FaceSetResult two = panelize_faces(set, "iso_grid", {{"size", 800.0}}, 2);
  EXPECT_EQ(one.combined.mesh.panels, two.combined.mesh.panels);
  EXPECT_EQ(one.combined.mesh.xyz, two.combined.mesh.xyz);
  EXPECT_EQ(one.combined.metrics.deviation, two.combined.metrics.deviation);
  EXPECT_EQ(one.panel_face, two.panel_face);
}

TEST(FaceSet, FacesTouchingAlongUnsharedEdgesAreSewn) {
  const FaceSet sewn_already = FaceSet::from_brep_string(split_patch());
  EXPECT_FALSE(sewn_already.sewn());
  // Built apart: sewn, in the order given, the cut one shared edge; the
  // result the same as the sewn shell's.
  const FaceSet apart = FaceSet::from_brep_string(unsewn_patch(0.0));
  ASSERT_EQ(apart.size(), 2u);
  EXPECT_TRUE(apart.sewn());
  EXPECT_EQ(apart.shared_edge_count(), 1u);
  EXPECT_LT(apart.face(0)->bounds().u_max, 0.4 + 1e-9);
  const FaceSetResult a = panelize_faces(apart, "equal_size_grid", {{"size", 900.0}});
  const FaceSetResult b = panelize_faces(sewn_already, "equal_size_grid", {{"size", 900.0}});
  EXPECT_EQ(a.combined.mesh.panels.size(), b.combined.mesh.panels.size());
  EXPECT_EQ(a.shared_edge_nodes, b.shared_edge_nodes);
  // Lifted by 1 mm (1e-5 of the size is about 0.12 mm): not sewn, no shared edge.
  const FaceSet lifted = FaceSet::from_brep_string(unsewn_patch(1.0));
  EXPECT_FALSE(lifted.sewn());
  EXPECT_EQ(lifted.shared_edge_count(), 0u);
}

TEST(FaceSet, RefusesWhatItCannotJoin) {
  EXPECT_THROW(FaceSet::from_brep_string("not a brep"), InvalidGeometry);
  const FaceSet box =
      FaceSet::from_brep_string(test::brep(BRepPrimAPI_MakeBox(100, 200, 300).Shape()));
  EXPECT_EQ(box.size(), 6u);
  EXPECT_EQ(box.shared_edge_count(), 12u);
  EXPECT_THROW(panelize_faces(box, "guide_line_scaling", {{"rod_length", 50.0}}), InvalidParameter);
  // A box panelized whole: its corners are single nodes of three faces.
  const FaceSetResult r = panelize_faces(box, "iso_grid", {{"size", 40.0}});
  int corners = 0;
  for (const Vec3& p : r.combined.mesh.xyz) {
    const bool corner = (p.x() == 0 || std::abs(p.x() - 100) < 1e-9) &&
                        (p.y() == 0 || std::abs(p.y() - 200) < 1e-9) &&
                        (p.z() == 0 || std::abs(p.z() - 300) < 1e-9);
    corners += corner ? 1 : 0;
  }
  EXPECT_EQ(corners, 8);
  // Box faces tile exactly: their panels' areas add up to the box's surface.
  double area = 0;
  for (double a : r.combined.metrics.area) area += a;
  EXPECT_NEAR(area, 2 * (100 * 200 + 100 * 300 + 200 * 300), 1e-6);
}

}  // namespace
}  // namespace tessella
