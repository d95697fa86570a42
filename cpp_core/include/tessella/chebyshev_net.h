// A Chebyshev net (the "compass" or fishnet construction of timber grid
// shells): every interior rod is exactly `size` long, so all full panels are
// skew rhombi with four equal sides that differ only by their two diagonals.
// That makes the layout the one made for repetition (issue 17: panel families
// within a tolerance), and a grid shell of equal members.
//
// Construction: two generators through the seed, the face's u and v
// iso-curves (or two crossing guide curves, the seed their crossing), are
// divided into equal chords of `size`; every further node is
// the surface point at distance `size` from its two known neighbours (the
// intersection of two spheres with the surface, Newton in (u,v) from the
// parallelogram guess), quadrant by quadrant away from the seed.
//
// Where the rule fails (the surface's edge, a shear sharper than
// kChebyshevMinShearDeg, Newton not converging), a node takes the
// parallelogram guess in (u,v) instead and the rule goes on from it, so a
// failure stays local: rods at a guess are not of equal length (counted in
// the report). The lattice is extended by guesses past the face's (u,v)
// bounds and cut by the trims like the relaxed grid's cells
// (mesh/cell_clipping.h), so the panels tile the face. Where guesses fold
// (no Chebyshev net covers a region of total curvature over 2 pi: a whole
// sphere), the lattice is laid out again as a Tutte embedding round the
// net, freeing the net's nodes near the folds until none is left.
#pragma once

#include "tessella/grid_methods.h"
#include "tessella/methods.h"
#include "tessella/panel_mesh.h"

namespace tessella {

class SurfaceFace;

// Below this angle between two rods of a cell (3D) the net stops: a rhombus
// sheared further is a sliver and its neighbours fold soon after.
constexpr double kChebyshevMinShearDeg = 20.0;

struct ChebyshevNetParams {
  double size = 0.0;  // rod length, mm (required)
  // The seed (where the two generators cross) as fractions of the face's
  // (u,v) bounds.
  double seed_u = 0.5;
  double seed_v = 0.5;
  // Two crossing curves (3D polylines on or near the face) to take as the
  // generators instead of the iso-lines: the seed is their first crossing,
  // and the net's rows run along them (a grid shell's chosen lines; the
  // lines a roof was cut along into faces of one surface, which then share
  // one net whose rows are the cuts). Empty: the iso-lines through the seed.
  Polylines guides;
  GridClipParams clip;
};

struct ChebyshevNetReport {
  int net_nodes = 0;                 // nodes inside the face at `size` from their neighbours
  int extrapolated_nodes = 0;        // parallelogram guesses inside the face
  int lattice_u = 0, lattice_v = 0;  // nodes of the lattice before the cut
};

PanelMesh chebyshev_net(const SurfaceFace& face, const ChebyshevNetParams& params,
                        ChebyshevNetReport* report = nullptr);

// The lattice alone, in (u,v), nu x nv nodes row by row (node (i,j) at
// j * nu + i), before the trim cut; `on_net[k]` tells the nodes of the net.
struct ChebyshevLattice {
  std::vector<Vec2> uv;
  std::vector<char> on_net;
  int nu = 0, nv = 0;
};
// cuts: (u,v) polylines on the face's surface that guides running along
// them follow (a face set's trims, the lines it was cut along; see
// methods/grids/path_along_cuts.h). None for one face.
ChebyshevLattice chebyshev_lattice(const SurfaceFace& face, const ChebyshevNetParams& params,
                                   const std::vector<std::vector<Vec2>>& cuts = {});

// A lattice cut by the face's trims: chebyshev_net's last step. A face set
// makes one lattice on the union of the faces lying on one surface and cuts
// it by each, so the net's rows and equal rods run on across their edges.
PanelMesh chebyshev_net_on_lattice(const SurfaceFace& face, const ChebyshevLattice& lattice,
                                   const GridClipParams& clip);

// Parameters from values as the method declarations read them (checked).
ChebyshevNetParams chebyshev_net_params(const ParamValues& values);

}  // namespace tessella
