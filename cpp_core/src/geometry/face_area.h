#pragma once

#include <TopoDS_Face.hxx>

namespace tessella {

// The area of a trimmed face, to about 1e-6 relative or better.
//
// OCCT's fixed-order Gauss integration (BRepGProp::SurfaceProperties without
// a tolerance) is exact to ~1e-13 on polynomial surfaces and trims but not on
// rational ones: a NURBS sphere comes out 0.37% large, a NURBS cylinder's
// band 0.27%, a disk trimmed by a rational circle 0.16% small. The coverage
// check compares the panels' area with the face's within 0.1%, so such a face
// was refused as "overlapping". Where the surface or a trim curve is rational
// (or of a kind whose rationality is not known) the area comes from OCCT's
// adaptive integration instead; it costs 10-100 times as much, so
// polynomial faces keep the Gauss rule. A surface of linear extrusion, on
// which the adaptive rule itself goes wrong, is integrated as its NURBS copy.
double face_area(const TopoDS_Face& face);

// True where the fixed-order rule may be inexact: the surface or one of the
// face's trim curves in (u,v) is rational, or not a known polynomial kind.
bool face_has_rational_geometry(const TopoDS_Face& face);

}  // namespace tessella
