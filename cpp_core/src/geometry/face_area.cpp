#include "geometry/face_area.h"

#include <BRepAdaptor_Curve2d.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <cmath>

namespace tessella {

namespace {

// Relative accuracy asked of the adaptive rule. Its own estimate is loose:
// at 1e-7 a NURBS cylinder band came out 3e-6 off; at 1e-9 within 1e-6 (the
// test), still cheap (a NURBS disk 0.1 ms, a band 0.3 ms).
constexpr double kAdaptiveAccuracy = 1e-9;

bool surface_is_rational(const BRepAdaptor_Surface& s) {
  switch (s.GetType()) {
    case GeomAbs_Plane:
    case GeomAbs_Cylinder:
    case GeomAbs_Cone:
    case GeomAbs_Sphere:
    case GeomAbs_Torus:
      return false;  // integrated in closed form per Gauss point: exact
    case GeomAbs_BSplineSurface:
    case GeomAbs_BezierSurface:
      return s.IsURational() || s.IsVRational();
    default:
      return true;  // revolved, extruded, offset...: not known to be polynomial
  }
}

bool pcurve_is_rational(const BRepAdaptor_Curve2d& c) {
  switch (c.GetType()) {
    case GeomAbs_Line:
    case GeomAbs_Circle:  // trigonometric: the Gauss rule is exact to ~1e-16 on these
    case GeomAbs_Ellipse:
      return false;
    case GeomAbs_BSplineCurve:
    case GeomAbs_BezierCurve:
      return c.IsRational();
    default:
      return true;
  }
}

}  // namespace

bool face_has_rational_geometry(const TopoDS_Face& face) {
  if (surface_is_rational(BRepAdaptor_Surface(face, false))) return true;
  for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) {
    try {
      if (pcurve_is_rational(BRepAdaptor_Curve2d(TopoDS::Edge(e.Current()), face))) return true;
    } catch (const Standard_Failure&) {
      return true;  // no pcurve to inspect: let the adaptive rule decide
    }
  }
  return false;
}

double face_area(const TopoDS_Face& face) {
  GProp_GProps props;
  // OCCT's adaptive rule goes wrong on a surface of linear extrusion: a
  // closed B-spline curve extruded came out 0.5% to 7% off (bench_faces'
  // random extrusions; the fixed rule 0.2%), and walking_agent's correct
  // panels on it were refused as overlapping. The face converted to NURBS
  // (exact for an extrusion: degree 1 along it) integrates to 1e-8.
  if (BRepAdaptor_Surface(face, false).GetType() == GeomAbs_SurfaceOfExtrusion) {
    try {
      BRepBuilderAPI_NurbsConvert convert(face, Standard_True);
      if (convert.IsDone() && convert.Shape().ShapeType() == TopAbs_FACE) {
        BRepGProp::SurfaceProperties(TopoDS::Face(convert.Shape()), props, kAdaptiveAccuracy);
        return std::abs(props.Mass());
      }
    } catch (const Standard_Failure&) {  // the face as it is, below
    }
    props = GProp_GProps();
  }
  if (face_has_rational_geometry(face))
    BRepGProp::SurfaceProperties(face, props, kAdaptiveAccuracy);
  else
    BRepGProp::SurfaceProperties(face, props);
  return std::abs(props.Mass());
}

}  // namespace tessella
