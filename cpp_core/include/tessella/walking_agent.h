// The walking-agent method of seed 000 (MSc thesis "Tessellation of arbitrarily
// shaped objects", section 4, appendix III) and its bottom-up rival, the
// gradient-descent step rule (section 5.2, appendix V).
//
// Design (an adaptive TENSOR grid): the thesis' agents walk the u edge and the
// v edge with a fixed sample step, grow the panel edge while the chord
// deviation (distance between the chord midpoint and the surface point halfway
// along the walked path) stays under max_deviation and the chord under
// max_size, then step back by a tenth of a step and place a node. Here the
// u-edge agent has a twin on every sample row across the face (one row per
// sample step, walking in lockstep), and a u node is placed where ANY row's
// agent breaks the rule; the node becomes an iso-u grid line. The v agents do
// the same. The lines therefore form a tensor grid whose spacing the agents
// decide locally (dense where the surface bends, sparse where it is flat), so
// the layout is always consistent rows of quads and is cut by the trim with
// clip_grid exactly like the foundation's grids. The diagonal walkers start
// from the edge nodes and walk the cell diagonals (u-v direction); a cell
// whose diagonal chord deviation exceeds diagonal_deviation gets an extra
// line. What the tensor design gives up: a line placed for a curved region
// runs through the whole face (a cross-shaped band of density instead of a
// spot).
//
// Beyond the thesis, the bound holds for whole panels: every panel's model
// (bilinear quad, triangulated n-gon) is compared with the surface at the same
// (u,v) (an upper bound of the distance to the surface) on a sample grid; a
// quad over the bound is folded into two flat triangles along its better
// diagonal when both meet the bound (recorded in PanelMesh::folds), otherwise
// a grid line is inserted through it, until no panel is over the bound.
#pragma once

#include <string>
#include <vector>

#include "tessella/grid_methods.h"
#include "tessella/methods.h"
#include "tessella/panel_mesh.h"

namespace tessella {

class SurfaceFace;

// Where the agents start: a corner of the (u,v) domain, from which they walk
// towards the opposite edges, or "max_curvature": the sample node with the
// largest chord deviation, from which they walk both ways (thesis, future work).
// Corners: "u_min_v_min", "u_max_v_min", "u_min_v_max", "u_max_v_max".
bool is_valid_agent_start(const std::string& start);

struct WalkingAgentParams {
  double max_deviation = 0.0;       // mm, required: chord / panel deviation bound
  double max_size = 0.0;            // mm, longest panel edge (chord); 0 = no limit
  double diagonal_deviation = 0.0;  // mm, bound of the diagonal walkers; 0 = 2 x max_deviation
  double sample_step = 0.05;        // fraction of the parameter span (thesis: 0.05)
  std::string start = "u_min_v_min";
  // The agents' edge rule uses edge_share x max_deviation (0 = try 1, 0.7 and
  // 0.5 and keep the layout with the fewest panels; see walking_agent.cpp).
  double edge_share = 0.0;
  // Rounds of the hard-bound refinement before giving up with an error.
  int max_refinements = 40;
  // Keep the coarsest iso grid (u_count x v_count over the face's bounds,
  // quads folded where that holds the bound, no panel cut by a trim) that
  // holds the bound with fewer panels than the agents' layout, if any.
  bool iso_fallback = true;
  // Let lines stop where the surface no longer needs them: neighbouring whole
  // cells merge wherever the merged panel holds the bound (panels of five or
  // six corners where a line ends; methods/agents/local_lines.h). False: the
  // thesis' lines across the whole face.
  bool local_lines = true;
  GridClipParams clip;
};

struct WalkingAgentReport {
  int folds = 0;              // quads folded into two triangles
  int inserted_lines = 0;     // lines added by the diagonal walkers and the bound
  int refinement_rounds = 0;  // rounds of the hard bound
  int bound_lines = 0;        // lines the hard bound inserted
  double max_estimate = 0.0;  // largest panel deviation estimate at the end (mm)
  double edge_share = 1.0;    // share of the bound the kept layout was walked with
  double grid_cells = 0.0;    // cells of the agents' line grid (before the trim cut)
  double grid_panels = 0.0;   // the agents' panels before lines stopped early (folds: two)
  // The coarsest iso grid holding the bound, kept instead of the agents'
  // layout because it has fewer panels (0 x 0: the agents' layout kept).
  int iso_u_count = 0, iso_v_count = 0;
  int merged_cells = 0;  // merges of neighbouring cells (lines stopped early)
};

PanelMesh walking_agent(const SurfaceFace& face, const WalkingAgentParams& params,
                        WalkingAgentReport* report = nullptr);

// Faces cut from one surface (a face set's faces on one surface, split as
// seed 004 splits its roof) walk their lines once, on their union, so that
// the rows run on across the cuts (issue 14): the lines of walking_agent's
// layout on `face` (the agents' lines after the hard bound, or the iso
// fallback's grid), then, on each face cut from it, the hard bound, the
// lines stopping early and the folds from those lines (the ones within the
// face's own bounds): no walk, no other share, no iso search of its own.
struct WalkingAgentLines {
  std::vector<double> u, v;  // increasing, from the bounds' minimum to their maximum
};
// `pinned`: values that must be lines (the faces' cuts along iso-lines of
// the surface): the nearest line of the layout moves onto each (by at most
// half a cell; one is added where the nearest is a bound), then the hard
// bound runs again on the union. A cut that is a line costs no panels (a
// panel across it would be cut in two) and the rows still carry on.
WalkingAgentLines walking_agent_lines(const SurfaceFace& face, const WalkingAgentParams& params,
                                      const WalkingAgentLines& pinned = {});
PanelMesh walking_agent_on_lines(const SurfaceFace& face, const WalkingAgentParams& params,
                                 const WalkingAgentLines& lines,
                                 WalkingAgentReport* report = nullptr);

// Parameters from values as the method declaration reads them (checked).
WalkingAgentParams walking_agent_params(const ParamValues& values);

// The gradient-descent rival: the next step from the previous two,
//   step_a = max_deviation * (step_{a-1} + step_{a-2}) / (dev_{a-1} + dev_{a-2}),
// the first step being sample_step (thesis: "taken arbitrarily"). Two samples
// per node; no step back and no panel check, so it may overshoot the bound (the
// thesis found up to ~45 times). Same tensor layout and trim cut as above.
struct GradientDescentParams {
  double max_deviation = 0.0;  // mm, required: the target ("optimal") deviation
  double sample_step = 0.05;   // fraction of the parameter span: the first step
  double max_step = 0.25;      // fraction of the span: longest step (thesis' cap)
  std::string start = "u_min_v_min";
  GridClipParams clip;
};

PanelMesh gradient_descent(const SurfaceFace& face, const GradientDescentParams& params);

}  // namespace tessella
