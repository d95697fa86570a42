// Faces of a set on different surfaces that meet tangentially along shared
// edges (G1 within kSmoothAngleDeg): a roof made of four B-spline
// sub-surfaces, patches of a façade, a box and its fillets. boundary_driven
// traces its curves across such a group (bd_across_surfaces.h), so the rows
// carry on across the edges.
#pragma once

#include <array>
#include <vector>

#include "faceset/face_set_impl.h"
#include "geometry/edge_track.h"
#include "tessella/vec.h"

namespace tessella {

// Normals of the two faces at most this far apart along the whole edge
// (sampled): the faces meet tangentially there.
constexpr double kSmoothAngleDeg = 10.0;

// Whether the normals of the edge's two faces agree (up to orientation:
// faces of an unsewn compound may face either way) within kSmoothAngleDeg at
// 9 points along it.
bool meets_tangentially(const SharedEdge& e, const SurfaceFace& a, const SurfaceFace& b);

struct SmoothEdge {
  std::array<int, 2> faces{};
  EdgeTrack polyline;  // the edge in 3D, within `tolerance` / 4 of its curve
};

struct SmoothLayout {
  std::vector<SmoothEdge> edges;
  // Per face: its group (-1: none; a face alone is in no group), numbered
  // from the group of the largest face.
  std::vector<int> group;
};

// The smooth edges between faces `eligible` says may take part (faces on one
// surface traced as a union do not) and their groups. `tolerance`
// per face (mm): the edge's polyline is sampled finer than a quarter of the
// smaller of its two faces'.
SmoothLayout smooth_layout(const FaceSet::Impl& set, const std::vector<char>& eligible,
                           const std::vector<double>& tolerance);

}  // namespace tessella
