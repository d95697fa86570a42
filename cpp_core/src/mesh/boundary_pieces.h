// Boundary pieces: every panel that is not a plain triangle or a quad of four
// nodes (a panel cut at a trim, whose outline follows the trim curve, or a
// polygon of more than four nodes) becomes what a workshop makes of it:
//
//  - one flat sheet when it has at most three nodes: the plane through its
//    nodes, its trim edge projected onto that plane;
//  - else a sheet bent along at most `max_bends` lines between its nodes (the
//    node polygon's triangulation with the smallest largest fold whose
//    diagonals run inside the panel), each piece flat through three nodes;
//  - a panel of more nodes than that is first split into two panels by a new
//    rod between two of its nodes.
//
// Never a fan of folds: the outline points between two nodes lie on one piece
// plane, so the unfolded outline carries the trim edge as one smooth curve and
// only bend lines are folds. Nodes never move (rods still meet there); trim
// points move off the surface by their distance to the piece plane, and the
// deviation metric measures exactly that piece. Where the piece deviates from
// the surface by more than `max_deviation` (sampled as the metrics do, trim
// edge included) the trim point farthest from its piece plane becomes a node
// (a new rod end on the trim) and the panel is modelled again.
#pragma once

#include <vector>

#include "tessella/panel_mesh.h"

namespace tessella {

class SurfaceFace;

struct BoundaryPiecesParams {
  // Largest deviation (mm) of a piece from the surface before the piece is
  // refined; 0 = no refinement.
  double max_deviation = 0.0;
  // Samples per edge direction for that deviation (MetricsParams::samples).
  int samples = 8;
  // Least distance (mm, along the trim) of a new node from the other nodes:
  // refining never makes a rod shorter than this.
  double min_node_spacing = 0.0;
  // max_deviation is a bound every panel must meet (walking_agent's): a piece
  // over it is refined even where that needs a closer node.
  bool hard_bound = false;
  // Whether the stage may make trim points nodes (new rods): false keeps the
  // layout's nodes (boundary_driven's all-quad layout); a panel that would
  // need one stays a curved piece on the surface or keeps its deviation.
  bool may_add_nodes = true;
  // Most bend lines per panel (2: a five-node panel is bent twice; a panel of
  // more nodes is split by a new rod).
  int max_bends = 2;
};

struct BoundaryPiecesReport {
  std::vector<int> origin;    // per panel of the new mesh: its panel before the stage
  std::vector<char> changed;  // per panel of the new mesh: modelled (or split) here
  int modelled = 0;           // panels modelled as flat pieces
  int bends = 0;              // bend lines over all panels
  int split = 0;              // new rods that split a panel
  int refined = 0;            // trim points made nodes to meet max_deviation
};

// Models the pieces in place: moves trim points onto their piece planes, fills
// mesh.bends, splits panels (new rods) and rebuilds mesh.rods when it did.
BoundaryPiecesReport model_boundary_pieces(const SurfaceFace& face, PanelMesh& mesh,
                                           const BoundaryPiecesParams& params);

}  // namespace tessella
