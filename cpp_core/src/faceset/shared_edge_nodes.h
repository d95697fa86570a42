// Makes the meshes of a face set agree along the edges two faces share: after
// each face's method (and its short rods), before the metrics. Per shared
// edge, the nodes both faces have on it are merged into one list (coincident
// nodes become one; then a node of one face and the nearest neighbouring node
// of the other closer than `merge_distance` along the edge become one, where
// an edge end is, else where the lower face's is; a trim point where a node
// comes to sit is that node), each face takes every node of that list
// (inserted into its outline or moved onto it), and its outline runs straight
// from node to node there (the trim points between are dropped): both faces
// then have the same nodes and the same straight segments along the edge,
// with identical 3D positions, and no T-junction.
#pragma once

#include <vector>

#include "faceset/face_set_impl.h"
#include "tessella/panel_mesh.h"

namespace tessella {

struct SharedEdgeReport {
  int nodes = 0;       // nodes on shared edges (each counted once)
  int taken_over = 0;  // nodes a face inserted or moved to match its neighbour
  // Per face: the surface area (mm^2) between its shared edges and their
  // chords (2/3 chord x sagitta per segment), which its panels leave out or
  // cover beyond its trims; the coverage check allows it.
  std::vector<double> strip_area;
};

// meshes[i] is face i's mesh (set.faces order).
SharedEdgeReport conform_shared_edges(const FaceSet::Impl& set, std::vector<PanelMesh*>& meshes,
                                      double merge_distance);

}  // namespace tessella
