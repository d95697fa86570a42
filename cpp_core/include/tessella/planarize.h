// Planarization (issue 16, part 2): node moves that make every quad of a
// quad-dominant mesh planar within a tolerance while the nodes stay close to
// the surface and the mesh stays fair.
//
// A damped Gauss-Newton solver (each step solved by Eigen's conjugate
// gradients) on the quads' signed diagonal distances, with two more least-squares
// goals: closeness (each free node towards the band of max_deviation around
// the surface: its own place when inside) and fairness (the umbrella
// Laplacian of the moves over rods). With closeness on, a node a step puts
// outside the band goes back onto its edge (the band is a hard target); with
// closeness 0 nothing holds the nodes near the surface, as in libigl's
// planarize_quad_mesh. The best round is kept (most quads within
// planarity_tolerance, then the smallest worst one); rounds stop when every
// quad is planar and every node in the band, after 20 rounds without a better
// one, or after max_iterations. Nodes on the mesh boundary slide along their
// trims (put back exactly onto the trim's curve after every step) except at
// trim corners and B-rep vertices; the outlines of boundary pieces (panels
// with trim points) do not move. Deterministic.
#pragma once

#include "tessella/panel_mesh.h"
#include "tessella/surface_face.h"

namespace tessella {

struct PlanarizeParams {
  double planarity_tolerance = 1.0;  // mm, distance between a quad's diagonals; > 0
  double max_deviation = 20.0;       // mm, a node's largest distance from the surface; > 0
  // Weights against the planarity goal's 1 per quad (mm^2). Small ones: a
  // node inside the band is held where it is by its closeness goal, and the
  // fairness goal holds the input's shape, so both slow the quads down.
  double closeness = 0.1;   // the closeness goal (0: off, as libigl's planarize_quad_mesh)
  double fairness = 0.001;  // the fairness goal
  int max_iterations = 200;
  // Boundary nodes slide along their trims (away from trim corners and B-rep
  // vertices; not those of boundary pieces, whose outlines follow the trim).
  bool slide_on_trims = true;
};

struct PlanarizeReport {
  int quads = 0;  // panels of four nodes (the ones made planar)
  // Quads within planarity_tolerance, and the largest diagonal distance (mm).
  int planar_before = 0, planar_after = 0;
  double max_planarity_before = 0, max_planarity_after = 0;
  // Largest distance of a node from the surface (mm).
  double max_node_deviation_before = 0, max_node_deviation_after = 0;
  double max_move = 0;  // mm
  int iterations = 0;
  bool converged = false;  // every quad planar and every node in the band
  int sliding_nodes = 0;   // boundary nodes that slid along their trims
  double seconds = 0;      // wall time of the step
};

// Distance (mm) between the diagonals of quad p (as skew lines).
double diagonal_distance(const std::vector<Vec3>& p);

// The mesh with its free nodes moved (xyz; uv of their closest surface
// points). Throws InvalidParameter for a bad parameter.
PanelMesh planarize(const SurfaceFace& face, const PanelMesh& mesh, const PlanarizeParams& params,
                    PlanarizeReport* report = nullptr);

}  // namespace tessella
