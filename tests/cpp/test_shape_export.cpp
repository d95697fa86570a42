// Shape export: the panels compound shares vertices and edges between
// neighbouring panels and stays a valid shape with the panels' own geometry.
#include <gtest/gtest.h>

#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <GProp_GProps.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Iterator.hxx>
#include <sstream>

#include "tessella/errors.h"
#include "tessella/panel_mesh.h"
#include "tessella/shape_export.h"

using namespace tessella;

namespace {

// A 3 x 2 grid of 1000 mm quads on z = 0, with the middle node of the top
// row lifted by `h` (its two quads bent: bilinear faces), the rest flat.
PanelMesh grid(double h) {
  PanelMesh m;
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 3; ++i) {
      m.uv.emplace_back(1000.0 * i, 1000.0 * j);
      m.xyz.emplace_back(1000.0 * i, 1000.0 * j, (i == 1 && j == 2) ? h : 0.0);
    }
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) {
      const int a = 4 * j + i;
      m.panels.push_back({a, a + 1, a + 5, a + 4});
    }
  build_rods(m);
  return m;
}

TopoDS_Shape read(const std::string& s) {
  TopoDS_Shape shape;
  std::istringstream in(s);
  BRep_Builder b;
  BRepTools::Read(shape, in, b);
  return shape;
}

}  // namespace

TEST(ShapeExport, NeighbouringPanelsShareEdgesAndVertices) {
  for (double h : {0.0, 150.0}) {
    const TopoDS_Shape shape = read(panels_to_brep(grid(h), 1e-3));
    ASSERT_FALSE(shape.IsNull());
    EXPECT_TRUE(BRepCheck_Analyzer(shape).IsValid()) << h;
    int children = 0;
    for (TopoDS_Iterator it(shape); it.More(); it.Next()) ++children;
    EXPECT_EQ(children, 6);
    TopTools_IndexedMapOfShape faces, edges, vertices;
    TopExp::MapShapes(shape, TopAbs_FACE, faces);
    TopExp::MapShapes(shape, TopAbs_EDGE, edges);
    TopExp::MapShapes(shape, TopAbs_VERTEX, vertices);
    EXPECT_EQ(faces.Extent(), 6);
    EXPECT_EQ(edges.Extent(), 17);  // the grid's rods: 3 x 3 + 4 x 2
    EXPECT_EQ(vertices.Extent(), 12);
  }
}

TEST(ShapeExport, BentQuadsKeepTheirBilinearArea) {
  // The lifted node: the two quads touching it are bilinear patches; the area
  // of each is that of the patch (checked against the flat case and a fine
  // sum of the patch's own triangles).
  const double h = 300.0;
  const TopoDS_Shape shape = read(panels_to_brep(grid(h), 1e-3));
  std::vector<double> area;
  for (TopoDS_Iterator it(shape); it.More(); it.Next()) {
    GProp_GProps props;
    BRepGProp::SurfaceProperties(it.Value(), props);
    area.push_back(props.Mass());
  }
  ASSERT_EQ(area.size(), 6u);
  // bilinear patch over the unit square with one corner lifted by h: fine
  // midpoint sum of |Su x Sv| with S(u,v) = (1000u, 1000v, h u v) (or mirrored)
  const int n = 400;
  double bent = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double u = (i + 0.5) / n, v = (j + 0.5) / n;
      const double zu = h * v, zv = h * u;  // dz/du, dz/dv (mm per unit)
      bent += std::sqrt(1e12 + 1e6 * (zu * zu + zv * zv)) / (n * n);
    }
  for (int k : {0, 1, 2, 5}) EXPECT_NEAR(area[k], 1e6, 1e-3) << k;
  for (int k : {3, 4}) EXPECT_NEAR(area[k], bent, 1e-6 * bent) << k;
}

TEST(ShapeExport, FaceListDescribesThePanelsAsBuilt) {
  const PanelMesh m = grid(150.0);
  const PanelFaceList f = panel_faces(m, 1e-3);
  ASSERT_EQ(f.panel_offsets, (std::vector<int>{0, 1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(f.compound, (std::vector<char>{0, 0, 0, 0, 0, 0}));
  // the two quads at the lifted node are bilinear, the others flat on z = 0
  EXPECT_EQ(f.bilinear, (std::vector<char>{0, 0, 0, 1, 1, 0}));
  ASSERT_EQ(f.corner_offsets.size(), 7u);
  for (std::size_t k = 0; k < 6; ++k) {
    const std::vector<int> corners(f.corners.begin() + f.corner_offsets[k],
                                   f.corners.begin() + f.corner_offsets[k + 1]);
    EXPECT_EQ(corners, m.panels[k]);
    if (f.bilinear[k]) continue;
    EXPECT_NEAR(f.normal[k].z(), 1.0, 1e-12);
    EXPECT_NEAR(f.origin[k].z(), 0.0, 1e-12);
    EXPECT_LE(f.tolerance[k], 1e-9);
  }
  EXPECT_THROW(panel_faces(m, 0.0), InvalidParameter);
}
