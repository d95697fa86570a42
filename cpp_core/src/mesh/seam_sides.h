// One mesh across a periodic face's seam. A method that traces a face closed
// round its period (a full cylinder side) from its trim meets the seam from
// both sides: each side puts its own nodes on it, at u0 and at u0 + period.
// Joined here as the faces of a set are along a shared edge: one vertex per
// position, and every panel side along the seam passes through every seam
// vertex between its ends (no T-junction, one rod per segment).
#pragma once

#include <vector>

#include "tessella/panel_mesh.h"
#include "tessella/surface_face.h"

namespace tessella {

// Whether the face's (u,v) domain spans a whole period in u or in v (its
// seam lies inside it).
bool closed_round_a_seam(const SurfaceFace& face);

// Whether the face's domain spans a whole period along u (axis 0) or v (1).
bool closed_along(const SurfaceFace& face, int axis);

// Whether the (u,v) segment a-b runs along the seam of a face closed round its
// period (either copy of it): a trim there is no edge of the surface.
bool runs_along_seam(const SurfaceFace& face, const Vec2& a, const Vec2& b);

// The 3D lengths of the trim runs that go once round a closed direction
// between two seam crossings (a full cylinder's or a cone's two rims, a
// dome's rim; a pole's collapsed stretch does not count), longest first;
// none on a face not closed round a seam.
std::vector<double> rim_lengths(const SurfaceFace& face, const std::vector<TrimLoop>& loops);

// What to add to a corner's coordinate along a closed direction to read it
// on the previous corner's side of the seam: a period less or more where it
// is more than three quarters of one from the previous, else 0 (a panel
// across the seam jumps by nearly a period, while a coarse panel may span
// half of one exactly: a cylinder cut in two). The coverage check and
// panel_turn read corners by this one rule.
inline double seam_shift(double previous, double next, double period) {
  const double step = next - previous;
  if (step > 0.75 * period) return -period;
  if (step < -0.75 * period) return period;
  return 0.0;
}

// The largest share of a period that a panel with these corners spans
// round a closed direction (corners at a pole left out; corners read by
// seam_shift); 0 on a face not closed round a seam. At half or more a panel is no
// sheet a workshop can bend: two such make a cylinder two flat panels
// through its axis, one a ring.
double panel_turn(const SurfaceFace& face, const std::vector<Vec2>& corner_uv);

// The largest panel_turn of the mesh's panels.
double widest_panel_round(const SurfaceFace& face, const PanelMesh& mesh);

// The fewest cells a grid (iso_grid, equal_size_grid, walking_agent's lines)
// takes along u (along_u) or v: across a face closed in it (the whole
// period) three, since one cell's corners coincide and two make the same
// flat panel twice (a plane through the axis); between two poles (a
// sphere's v) two, since one cell spans pole to pole and its corners are two
// points. A size coarser than that (a fillet's small sphere in a face set)
// gets these counts, not an empty grid.
int fewest_cells_along(const SurfaceFace& face, bool along_u);

// A closed face whose seam edge's two pcurves lie a hair more or less than a
// period apart (up to 1e-6 of it; a STEP file's, FreeCAD's CAP_50SGV
// capacitor: 5.9e-7 of its period, the two copies 4.6e-6 mm apart in space)
// and whose copies are farther apart in space than the seam weld's 1e-9 of
// the face: the vertices on the two copies within 1e-6 of the face's size
// are one (each method put a node on each copy). Nothing on any other face.
void weld_loose_seam(const SurfaceFace& face, PanelMesh& mesh);

// Welds the two sides of the seam (mesh.corner_uv keeps each panel's own
// (u,v)) and inserts into each panel side along the seam the seam vertices
// strictly between its ends; likewise along the sides of a face closed on
// itself (its two sides one curve in space, the surface not periodic there;
// a pole at an end of that curve as on a cone). Nothing for any other face.
void join_seam_sides(const SurfaceFace& face, PanelMesh& mesh);

}  // namespace tessella
