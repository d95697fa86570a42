// Boundary-driven meshing across faces on different surfaces that meet
// tangentially (issue 14): a roof made of four B-spline sub-surfaces, a
// façade whose patches join with G1 continuity.
//
// Faces on one surface trace their curves once on the union
// (bd_across_faces.h). Faces on different surfaces have no common (u,v);
// a group of them joined by smooth edges is traced as one face would be
// (trace_bd_curves_across): the field's sources are the group's free
// boundary (its trims less the smooth edges between its faces: seed 001's
// sources are the boundary of the design, not the cuts a modeller made in
// it), the seeds are spaced along that boundary as along one face's trims,
// and a curve that reaches a smooth edge goes on into the face across it.
// Each face then builds its network from the pieces on it; the crossings of
// a smooth edge are nodes on both sides (pinned there).
#pragma once

#include <vector>

#include "geometry/edge_track.h"
#include "methods/boundary_driven/bd_curves.h"
#include "methods/boundary_driven/bd_tensor.h"
#include "tessella/boundary_driven.h"
#include "tessella/panel_mesh.h"

namespace tessella {

// A face of a smooth group.
struct BdGroupMember {
  const SurfaceFace* face = nullptr;
  std::vector<BdPolyline> boundary;  // its trims, as boundary_driven takes them
  std::vector<EdgeTrack> smooth;     // its smooth edges to other members
  std::vector<int> smooth_to;        // the member across each
  double tolerance = 0;              // a trim point within this of an edge lies on it (mm)
};

// A point within this distance (mm) of an edge's polyline lies on the edge:
// the trim polylines of two faces discretize their common edge apart, each
// within its deflection of it.
double bd_edge_tolerance(const SurfaceFace& face, const BoundaryDrivenParams& params);

// The member's trims and tolerance (its smooth edges are the caller's).
BdGroupMember bd_group_member(const SurfaceFace& face, const BoundaryDrivenParams& params);

// The curves of boundary_driven traced across the group (above): per member,
// the pieces on it, and the spacing they were traced at. Throws
// GeometryFailure for a group without free boundary (closed on itself, a
// filleted box: nothing to start from; its faces trace their own curves).
struct BdGroupCurves {
  std::vector<std::vector<BdCurve>> curves;
  double spacing = 0;
};
BdGroupCurves trace_bd_group_curves(const std::vector<BdGroupMember>& members,
                                    const BoundaryDrivenParams& params);

// boundary_driven on a member from its pieces of the group's curves: its
// network, refinement and panels as for one face, the nodes on its smooth
// edges kept where the curves cross them. Throws as boundary_driven does
// (GeometryFailure: the caller meshes the face on its own).
PanelMesh boundary_driven_on_group_curves(const SurfaceFace& face,
                                          const BoundaryDrivenParams& params,
                                          const BdGroupMember& member, std::vector<BdCurve> curves,
                                          double spacing);

// Pieces of the group machinery, exposed for their tests:
// `face`'s trim polylines (`boundary`) except where they run along one of
// `skip` (within `tolerance`): loops off all of them whole, the others cut
// into open runs that keep the point where they meet a skipped stretch.
std::vector<BdPolyline> bd_free_boundary_runs(const std::vector<BdPolyline>& boundary,
                                              const std::vector<EdgeTrack>& skip, double tolerance);

// Seeds along the free boundary of a group, spaced as boundary_driven spaces
// them along one face's trims (every `spacing` between corners where the
// boundary turns by more than `corner_angle_deg`, at least four round a loop
// without corners), on the runs of all its faces joined end to end (ends
// within `tolerance`; a run may be joined reversed).
std::vector<Vec3> bd_chain_seeds(const std::vector<BdPolyline>& runs, double spacing,
                                 double corner_angle_deg, double tolerance);

}  // namespace tessella
