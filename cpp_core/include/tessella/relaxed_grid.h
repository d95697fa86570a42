// The top-down rival of the walking agent (seed 000, section 5.1, appendix IV,
// after Chris Williams' British Museum Great Court roof): a grid of fixed
// topology, u_count x v_count panels, whose nodes slide on the surface until
// the chord deviations of their four rods are in equilibrium.
//
// Force on a node: the sum over its rods of (rod's chord deviation) x (unit
// vector along the rod), so a node moves towards the neighbour whose rod bends
// more (the thesis' sign rule, footnote 7); only the tangential part
// q = f - (f.n)n moves it, mapped to (u,v) by the surface's first derivatives.
// Border nodes slide along their border, corners stay. The number of nodes
// never changes, so the method equalizes the deviation but cannot bound it.
//
// Trimmed faces: the relaxed cells tile the whole (u,v) bounds, and each is
// cut by the trims (mesh/cell_clipping.h): whole cells stay quads, cells at a
// trim follow it, so the panels tile the face as the grids' do.
#pragma once

#include "tessella/grid_methods.h"
#include "tessella/panel_mesh.h"

namespace tessella {

class SurfaceFace;

struct RelaxedGridParams {
  int u_count = 10;
  int v_count = 10;
  int max_iterations = 200;
  // Stop when no node moves more than this fraction of the parameter span.
  double tolerance = 1e-4;
  // Step of one iteration: a node moves at most weight x its mean rod length.
  double weight = 0.2;
  // Slivers, trim polylines and the panel limit, as for the grids.
  GridClipParams clip;
};

struct RelaxedGridReport {
  int iterations = 0;
  bool converged = false;
  double last_move = 0;  // largest node move of the last iteration (fraction of span)
};

PanelMesh relaxed_grid(const SurfaceFace& face, const RelaxedGridParams& params,
                       RelaxedGridReport* report = nullptr);

}  // namespace tessella
