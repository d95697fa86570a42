// Faces for the tests, built with OCCT directly and passed to the core as BRep
// strings, exactly as the FreeCAD side does.
#pragma once

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepTools.hxx>
#include <Geom_BezierSurface.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Pln.hxx>
#include <sstream>
#include <string>

#include "tessella/surface_face.h"

namespace tessella::test {

inline std::string brep(const TopoDS_Shape& s) {
  std::ostringstream out;
  BRepTools::Write(s, out);
  return out.str();
}

inline TopoDS_Face first_face(const TopoDS_Shape& s,
                              TopAbs_Orientation skip_none = TopAbs_EXTERNAL) {
  (void)skip_none;
  return TopoDS::Face(TopExp_Explorer(s, TopAbs_FACE).Current());
}

// The lateral face of a closed cylinder (periodic in u, one seam).
inline SurfaceFace cylinder_face(double r, double h) {
  BRepPrimAPI_MakeCylinder cyl(r, h);
  return SurfaceFace::from_brep_string(brep(cyl.Face()));
}

inline SurfaceFace sphere_face(double r) {
  BRepPrimAPI_MakeSphere sph(r);
  return SurfaceFace::from_brep_string(brep(first_face(sph.Shape())));
}

inline TopoDS_Wire rect_wire(double x0, double y0, double x1, double y1, bool clockwise) {
  BRepBuilderAPI_MakePolygon p;
  if (clockwise) {
    p.Add(gp_Pnt(x0, y0, 0)), p.Add(gp_Pnt(x0, y1, 0)), p.Add(gp_Pnt(x1, y1, 0)),
        p.Add(gp_Pnt(x1, y0, 0));
  } else {
    p.Add(gp_Pnt(x0, y0, 0)), p.Add(gp_Pnt(x1, y0, 0)), p.Add(gp_Pnt(x1, y1, 0)),
        p.Add(gp_Pnt(x0, y1, 0));
  }
  p.Close();
  return p.Wire();
}

// Square plate [0,size]^2 in z = 0 with a square hole [h0,h1]^2.
inline SurfaceFace plate_with_square_hole(double size, double h0, double h1) {
  BRepBuilderAPI_MakeFace mk(gp_Pln(), rect_wire(0, 0, size, size, false));
  mk.Add(rect_wire(h0, h0, h1, h1, true));
  return SurfaceFace::from_brep_string(brep(mk.Face()));
}

// The square [0,1000]^2 in z = 0 as a Bezier patch with x(u) = 400u + 600u^2:
// iso-u lines crowd near x = 0 four times more densely than near x = 1000.
inline SurfaceFace stretched_plate() {
  TColgp_Array2OfPnt poles(1, 3, 1, 2);
  const double xs[3] = {0, 200, 1000};
  for (int i = 1; i <= 3; ++i) {
    poles(i, 1) = gp_Pnt(xs[i - 1], 0, 0);
    poles(i, 2) = gp_Pnt(xs[i - 1], 1000, 0);
  }
  Handle(Geom_BezierSurface) s = new Geom_BezierSurface(poles);
  return SurfaceFace::from_brep_string(brep(BRepBuilderAPI_MakeFace(s, 1e-7).Face()));
}

}  // namespace tessella::test
