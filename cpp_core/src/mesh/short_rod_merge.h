// Merging nodes closer than a minimum rod length: a grid line that crosses the
// trim a few millimetres from a grid node or a trim corner leaves a rod no
// workshop can build (shorter than one hub). The pipeline runs this stage after
// every method.
//
// Each rod shorter than the limit (shortest first) is collapsed so that its two
// nodes become one:
//  - an interior node merged with a node on the trim moves onto it;
//  - two interior nodes meet at one of them or at their (u,v) midpoint;
//  - two trim nodes next to each other along the trim meet at one of them
//    (a trim corner is kept in preference to a grid/trim crossing) or at a
//    trim outline point between them; the node given up stays in the mesh as
//    an outline point, so the trim polyline is never changed and every node
//    on the trim keeps its exact position.
// Along the trim a collapse only hands the outline points between the two
// nodes from one boundary panel to its neighbour: the mesh boundary stays the
// same edge for edge. A collapse is kept only if every panel it changes stays a
// simple polygon of the mesh's orientation with at least three nodes (or
// vanishes, its area going to the panels around), no edge is used twice, the
// (u,v) area of the changed panels is conserved, and (with a deviation bound)
// no changed panel deviates more than the bound or than before; with
// keep_quads a mesh of quads only keeps every panel a quad (a rod that cannot
// go without a triangle stays, counted in the report). Among the
// possible collapses of a rod the one whose changed panels keep the longest
// shortest rod wins. Rods and folds are rebuilt afterwards.
#pragma once

#include "tessella/panel_mesh.h"

namespace tessella {

class SurfaceFace;

struct ShortRodMergeParams {
  // Rods shorter than this (mm) are collapsed; 0 = automatic
  // (automatic_min_rod_length).
  double min_rod_length = 0.0;
  // Deviation bound (mm) the changed panels must keep (0: not checked); a
  // panel already over it may not get worse.
  double max_deviation = 0.0;
  int samples = 8;  // samples per panel edge of the deviation measure
  // An all-quad mesh stays all quads (boundary_driven's layout: quads are its
  // point).
  bool keep_quads = false;
};

struct ShortRodMergeReport {
  double min_rod_length = 0.0;  // the limit used (mm)
  int merged = 0;               // collapsed rods (nodes merged)
  int remaining = 0;            // rods still shorter than the limit (no valid collapse)
};

// A quarter of the nominal panel edge, sqrt(mesh.nominal_area); a quarter of
// the median rod length if the mesh has no nominal area.
double automatic_min_rod_length(const PanelMesh& mesh);

// Collapses the rods of `mesh` shorter than the limit (see the file comment);
// fills mesh.corner_uv only where it was filled, fixes mesh.folds and rebuilds
// mesh.rods.
ShortRodMergeReport merge_short_rods(const SurfaceFace& face, PanelMesh& mesh,
                                     const ShortRodMergeParams& params);

}  // namespace tessella
