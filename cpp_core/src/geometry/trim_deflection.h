// The one rule for how finely the trim curves become (u,v) polylines: the
// shared parameter trim_deflection (mm) when it is > 0, else the automatic
// deflection kAutomaticTrimDeflection x the model size (the diagonal of the
// face's bounding box). Every method and stage that polygonizes the trim for
// its result (grid clipping, boundary-driven, the guide-line methods, the
// curve-family mesh) takes its deflection from here.
//
// The factor is the finest any method needs: the boundary-driven method
// places its trim nodes on the polyline vertices and chords and needs them
// within 1e-6 of the model size of the true trim (at 1e-6 x model size its
// nodes-on-surface-and-inside test fails). The polylines get about twice the
// points of 1e-6 x model size (points grow as 1 / sqrt(deflection)); measured
// on the bundled examples, that costs the grids and the agents 50-100% more CPU
// time, 60-70% of it in triangulating the boundary panels, which carry
// every trim point (triangulate_polygon in mesh/panel_model.cpp), and the
// guide-line methods 5-25%; the trim handling itself (trim_loops, the
// classifier, the clipping) stays a few per cent of the time.
#pragma once

#include "tessella/surface_face.h"

namespace tessella {

constexpr double kAutomaticTrimDeflection = 2.5e-7;

// kAutomaticTrimDeflection x face.model_size().
double automatic_trim_deflection(const SurfaceFace& face);

// `requested` when > 0, else automatic_trim_deflection(face).
double trim_deflection(const SurfaceFace& face, double requested);

// Coarse polylines for tests that only steer sampling, never bound a result:
// which rows the agents walk and which cells they refine, and the grids'
// arc-length averaging across the face. kSteeringTrimDeflection x the model size.
constexpr double kSteeringTrimDeflection = 1e-3;
double steering_trim_deflection(const SurfaceFace& face);

}  // namespace tessella
