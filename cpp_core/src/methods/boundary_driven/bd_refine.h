// Boundary-driven meshing, stage 5: refinement of the network's faces (seed 001
// section 3). Each step works on a BdNetwork's nodes and panels (its edges are
// not updated).
#pragma once

#include <vector>

#include "methods/boundary_driven/bd_network.h"

namespace tessella {

// Section 3.1: a triangle whose smallest / largest corner angle (3D) is under
// `ratio` loses the corner with the largest angle, which is replaced by the
// nearest other corner of the triangle. Trim corners are never removed; a node
// on the trim only merges into a node near it along the same loop (not one
// across a narrow strip or a notch; an interior node merging with a trim node
// keeps the trim node). Returns the number removed.
int remove_skewed_triangles(BdNetwork& net, double ratio);

// The same vertex replacement for the network's short edges (a generalization
// of section 3.1 we add: curves that cross or meet the trim close to another
// node leave tiny faces and sharp corners). Every panel edge shorter than
// `min_length` (mm, 3D) merges its two ends, under the same rules (trim corners
// stay, trim nodes merge only with nodes near them along their loop, an interior node merging with
// a trim node keeps the trim node; two interior nodes meet half-way, projected onto the surface). A
// merge that would make a panel visit a node twice is skipped. Returns the number of merges.
int collapse_short_edges(const SurfaceFace& face, BdNetwork& net, double min_length);

// Section 3.2: every panel with n corners becomes n quads by its centre and its
// edge midpoints (applied to all panels so neighbours stay conforming: a
// midpoint shared by two panels splits both). Midpoints of edges along the trim
// are placed on the trim polyline (half-way in arc length); other new nodes are
// projected onto the surface.
// Face sets (`short_shared_edge` > 0): a network face cut by an edge shared
// with another face is a strip between a curve and that edge; its sides
// shorter than `short_shared_edge` with one end on the shared edge (across
// the strip) get no midpoint, and such a quad is split across its length only
// (2 quads, not 4), where its neighbours allow it (a panel keeps sides without
// a midpoint only as a quad's opposite pair). A side along the edge (both
// ends on it) keeps its midpoint however short: without, a strip's quad had
// three bare sides, could not be split along, and gave every side of the
// strip a midpoint (a row of quarter panels along the edge).
void quadrangulate(const SurfaceFace& face, const std::vector<BdPolyline>& boundary, BdNetwork& net,
                   double short_shared_edge = 0.0);

// Section 3.3: Laplacian smoothing (eq. 3, equal weights, step `factor`).
// Interior nodes move toward the centroid of their neighbours and are projected
// back onto the surface; nodes on the trim move along their loop toward the
// middle of their two trim neighbours (so they stay on the trim polyline);
// corners stay fixed. A move that would fold a panel (in (u,v)) or leave more
// rods across a trim at the node (bd_trim_crossing.h) is skipped.
void smooth_bd_mesh(const SurfaceFace& face, const std::vector<BdPolyline>& boundary,
                    BdNetwork& net, int iterations, double factor = 0.5);

// Angle-aware node relocation (our addition after section 3.3): Laplacian
// smoothing cannot open a sharp corner where two trims are closer than a panel
// or where a triangle was quadrangulated (a quad with one flat corner). Every
// node of a panel with a corner under `target_deg` (3D) is moved, by local
// search, to the candidate position that maximizes the smallest corner angle
// of the panels around it (a reflex corner in (u,v) counts as 0 unless it is
// on a concave trim). Interior nodes try points toward and away from each
// neighbour and square to that edge in the tangent plane, projected onto the
// surface and inside the trim; trim nodes slide along their loop toward or
// away from their trim neighbours (so they stay on the trim polyline); corners
// stay fixed. A move is kept only when it raises that local minimum, makes
// no edge at the node shorter than 0.3 x the median edge (unless it already
// was and gets no shorter) and leaves no more rods across a trim (a quad
// beside a trim with both diagonals across it counts as one). A corner at a
// trim node is measured against the trim itself where the side runs along
// it (the first trim polyline point past the node, not the chord to the next
// trim node): a rod nearly along a hole's rim is a spike of the cut panel
// however wide the chord's angle. Returns the number of moves.
int improve_bd_angles(const SurfaceFace& face, const std::vector<BdPolyline>& boundary,
                      BdNetwork& net, double target_deg, int passes);

// Our addition: a network edge that crosses a trim (bd_trim_crossing.h) makes
// the panel beside it fold over the opening once it follows the trim. Its
// ends are moved, by the same local search, to the candidate position with
// the fewest such crossings at the node (then the best smallest angle; never
// one that folds a panel). The smoothing and the angle moves add no crossing
// themselves, but the curves' chords and the quadrangulation's new nodes can
// (trimmed_bspline_holes at 1200 mm: two edges from one trim node across a
// hole's bend). Runs on the final trim nodes, on the trims' own curves
// (SurfaceFace::snap_to_trim), against the trim polylines the panels'
// outlines follow: so it sees the crossings of the outlines as they will be
// (cone_facade at 900 mm: a rod 4 mm beside a hole's rim, crossing it only
// once its trim node was snapped). A trim node's candidates are snapped too.
// Returns the number of moves.
int untangle_trim_crossings(const SurfaceFace& face, const std::vector<BdPolyline>& boundary,
                            BdNetwork& net, int passes = 10);

}  // namespace tessella
