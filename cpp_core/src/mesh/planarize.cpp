#include "tessella/planarize.h"

#include <Eigen/Dense>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <set>

#include "geometry/trim_deflection.h"
#include "mesh/fixed_vertices.h"
#include "tessella/errors.h"
#include "tessella/progress.h"

namespace tessella {

double diagonal_distance(const std::vector<Vec3>& p) {
  if (p.size() != 4) return 0.0;
  const Vec3 d1 = p[2] - p[0], d2 = p[3] - p[1];
  const Vec3 n = d1.cross(d2);
  if (!(n.norm() > 1e-300)) return 0.0;
  return std::abs((p[1] - p[0]).dot(n)) / n.norm();
}

namespace {

// Levenberg-style damping of every Gauss-Newton step (per mm^2 of move):
// keeps the system positive definite with closeness and fairness off, and the
// steps short where the linearised diagonal distances mislead.
constexpr double kDamping = 1e-3;
// Rounds without a better one before the solver stops; it also stops when
// kPatience rounds together made fewer than kPlateauShare of the quads
// planar (the last few warped quads of a layout creep in over hundreds of
// rounds: 98.7% of the dome's quads in 60 rounds, 99.2% in 200).
constexpr int kPatience = 20;
constexpr double kPlateauShare = 1e-3;
// A sliding node's move across its trim's tangent: penalized this stiffly
// (per mm^2, against the planarity goal's 1 per quad).
constexpr double kSlideStiffness = 100.0;
// A boundary node turning more than this (deg) is a corner: it stays.
constexpr double kSlideTurnDeg = 30.0;

// A boundary node that slides along trim loop `loop` (-1: it does not), in
// the direction `tangent`, by at most `reach` (mm) a round.
struct TrimSlider {
  int loop = -1;
  Vec3 tangent = Vec3::Zero();
  double reach = 0;
};

// The nodes on the mesh's boundary (sides of one panel) that may slide: in
// no boundary piece (a panel with trim points would need its outline redone),
// on exactly two boundary sides, the boundary turning there by at most
// kSlideTurnDeg, and no B-rep vertex of the trim within 1e-6 of the model.
std::vector<TrimSlider> trim_sliders(const SurfaceFace& face, const PanelMesh& mesh) {
  const std::size_t nv = mesh.vertex_count();
  std::vector<TrimSlider> out(nv);
  const MeshBoundary boundary = mesh_boundary(mesh);
  const std::vector<std::vector<int>>& along = boundary.along;
  const std::vector<char>& in_piece = boundary.in_piece;
  const double ms = face.model_size();
  const std::vector<TrimLoop> loops = face.trim_loops(trim_deflection(face, 0.0));
  const double cos_turn = std::cos(kSlideTurnDeg * 3.14159265358979323846 / 180.0);
  for (std::size_t v = 0; v < nv; ++v) {
    if (along[v].size() != 2 || in_piece[v] || !is_node(mesh, static_cast<int>(v))) continue;
    const Vec3& x = mesh.xyz[v];
    const Vec3 back = x - mesh.xyz[static_cast<std::size_t>(along[v][0])];
    const Vec3 ahead = mesh.xyz[static_cast<std::size_t>(along[v][1])] - x;
    if (!(back.norm() > 0 && ahead.norm() > 0)) continue;
    if (back.normalized().dot(ahead.normalized()) < cos_turn) continue;
    int loop = -1;
    double nearest = std::numeric_limits<double>::infinity();
    bool at_vertex = false;
    for (std::size_t k = 0; k < loops.size(); ++k)
      for (std::size_t i = 0; i < loops[k].xyz.size(); ++i) {
        const double d = (loops[k].xyz[i] - x).norm();
        if (d < nearest) nearest = d, loop = static_cast<int>(k);
        if (i < loops[k].corner.size() && loops[k].corner[i] && d <= 1e-6 * ms) at_vertex = true;
      }
    if (at_vertex || loop < 0) continue;
    out[v].loop = loop;
    out[v].tangent = (back + ahead).normalized();
    out[v].reach = 0.25 * std::min(back.norm(), ahead.norm());
  }
  return out;
}

// Quads farther off planar than this many tolerances weigh in linearly.
constexpr double kHuberTolerances = 5.0;
// Conjugate-gradient iterations per Gauss-Newton step at most.
constexpr int kCgIterations = 15;

}  // namespace

PanelMesh planarize(const SurfaceFace& face, const PanelMesh& mesh, const PlanarizeParams& params,
                    PlanarizeReport* report) {
  require_in_range("planarity_tolerance (mm)", params.planarity_tolerance, 1e-12, 1e9);
  require_in_range("max_deviation (mm)", params.max_deviation, 1e-12, 1e9);
  require_in_range("closeness", params.closeness, 0.0, 1e6);
  require_in_range("fairness", params.fairness, 0.0, 1e6);
  require_in_range("max_iterations", params.max_iterations, 0, 100000);
  const auto started = std::chrono::steady_clock::now();
  PlanarizeReport rep;
  PanelMesh out = mesh;
  // Thousands of projections close together: the span-cached evaluation.
  const SurfaceFace::FastEvaluation fast(face);
  const std::size_t nv = mesh.vertex_count();
  // Quads: panels of four nodes.
  std::vector<std::array<int, 4>> quads;
  for (const auto& p : mesh.panels) {
    if (p.size() != 4) continue;
    bool nodes = true;
    for (int v : p) nodes = nodes && is_node(mesh, v);
    if (nodes) quads.push_back({p[0], p[1], p[2], p[3]});
  }
  rep.quads = static_cast<int>(quads.size());
  // Free nodes: nodes of a quad, not fixed, or sliding along their trim.
  const std::vector<char> fixed = fixed_vertices(mesh);
  const std::vector<TrimSlider> slider =
      params.slide_on_trims ? trim_sliders(face, mesh) : std::vector<TrimSlider>(nv);
  std::vector<int> index(nv, -1);
  std::vector<int> free;
  for (const auto& q : quads)
    for (int v : q)
      if ((!fixed[static_cast<std::size_t>(v)] || slider[static_cast<std::size_t>(v)].loop >= 0) &&
          index[static_cast<std::size_t>(v)] < 0) {
        index[static_cast<std::size_t>(v)] = static_cast<int>(free.size());
        free.push_back(v);
        rep.sliding_nodes += slider[static_cast<std::size_t>(v)].loop >= 0 ? 1 : 0;
      }
  auto quad_points = [&](const std::array<int, 4>& q) {
    return std::array<Vec3, 4>{
        out.xyz[static_cast<std::size_t>(q[0])], out.xyz[static_cast<std::size_t>(q[1])],
        out.xyz[static_cast<std::size_t>(q[2])], out.xyz[static_cast<std::size_t>(q[3])]};
  };
  auto planarity = [&](const std::array<int, 4>& q) {
    const auto x = quad_points(q);
    return diagonal_distance({x[0], x[1], x[2], x[3]});
  };
  // Each free node's foot on the surface (its uv carried from round to round).
  std::vector<Projection> foot(free.size());
  // `feet_known`: the round's step already projected every free node (its
  // foot is in `foot`), as it does with the band on.
  auto measure = [&](int& planar, double& worst, double& off, bool feet_known = false) {
    planar = 0, worst = 0, off = 0;
    for (const auto& q : quads) {
      const double d = planarity(q);
      planar += d <= params.planarity_tolerance ? 1 : 0;
      worst = std::max(worst, d);
    }
    for (std::size_t k = 0; k < free.size(); ++k) {
      const std::size_t v = static_cast<std::size_t>(free[k]);
      if (!feet_known) foot[k] = face.project(out.xyz[v], out.uv[v]);
      off = std::max(off, foot[k].distance);
    }
  };
  measure(rep.planar_before, rep.max_planarity_before, rep.max_node_deviation_before);
  const std::size_t n = free.size();
  // Planar and close already: nothing to move (a solve would round the nodes).
  const bool done =
      rep.planar_before == rep.quads && rep.max_node_deviation_before <= params.max_deviation;
  if (n > 0 && params.max_iterations > 0 && !done) {
    using Sparse = Eigen::SparseMatrix<double>;
    using Triplet = Eigen::Triplet<double>;
    const Eigen::Index dim = static_cast<Eigen::Index>(3 * n);
    // Fairness: the umbrella Laplacian of the free nodes over rods, as a
    // 3n x 3n operator on the free coordinates (fixed neighbours constant).
    std::vector<std::set<int>> nb(nv);
    for (const auto& p : mesh.panels) {
      std::vector<int> c;
      for (int v : p)
        if (is_node(mesh, v)) c.push_back(v);
      for (std::size_t i = 0; i < c.size(); ++i) {
        const int a = c[i], b = c[(i + 1) % c.size()];
        nb[static_cast<std::size_t>(a)].insert(b);
        nb[static_cast<std::size_t>(b)].insert(a);
      }
    }
    std::vector<Triplet> lt;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t v = static_cast<std::size_t>(free[k]);
      const double w = nb[v].empty() ? 0.0 : 1.0 / static_cast<double>(nb[v].size());
      for (int c = 0; c < 3; ++c) {
        const int row = static_cast<int>(3 * k) + c;
        lt.emplace_back(row, row, 1.0);
        for (int u : nb[v]) {
          const int j = index[static_cast<std::size_t>(u)];
          if (j >= 0) lt.emplace_back(row, 3 * j + c, -w);
        }
      }
    }
    Sparse l(dim, dim);
    l.setFromTriplets(lt.begin(), lt.end());
    const Sparse ltl = Sparse(l.transpose() * l);
    Eigen::VectorXd x0(dim);
    for (std::size_t k = 0; k < n; ++k)
      x0.segment<3>(static_cast<Eigen::Index>(3 * k)) = mesh.xyz[static_cast<std::size_t>(free[k])];
    // Conjugate gradients (Jacobi preconditioner): a Gauss-Newton step needs
    // no exact solve, and the sparse Cholesky of the 3n x 3n system cost 0.8 G
    // instructions a round on 2,000 quads (80% of the time).
    Eigen::ConjugateGradient<Sparse, Eigen::Lower | Eigen::Upper> solver;
    solver.setMaxIterations(kCgIterations);
    solver.setTolerance(1e-8);
    PanelMesh best = out;
    int best_planar = rep.planar_before, since_best = 0;
    std::vector<int> best_by_round;  // best_planar after each round
    double best_worst = rep.max_planarity_before;
    for (int round = 0; round < params.max_iterations; ++round) {
      report_stage(static_cast<double>(round) / params.max_iterations, "planarizing");
      rep.iterations = round + 1;
      // Gauss-Newton on the quads' signed diagonal distances c_q (their scale
      // |d1 x d2| held for the step), the band and fairness as least squares:
      //   (J^T J + (closeness + damping) I + fairness L^T L) dx
      //     = -(J^T c + closeness (x - band) + fairness L^T L (x - x0)).
      std::vector<Triplet> jt;
      Eigen::VectorXd c(static_cast<Eigen::Index>(quads.size()));
      for (std::size_t qi = 0; qi < quads.size(); ++qi) {
        const auto& q = quads[qi];
        const auto p = quad_points(q);
        const Vec3 a = p[1] - p[0], d1 = p[2] - p[0], d2 = p[3] - p[1];
        const Vec3 nrm = d1.cross(d2);
        const double scale = nrm.norm();
        if (!(scale > 1e-300)) {
          c(static_cast<Eigen::Index>(qi)) = 0;
          continue;
        }
        const double dist = a.dot(nrm) / scale;
        // Huber weights (iteratively reweighted): a quad far off planar (a
        // warped corner of the layout no band-bound move can flatten) counts
        // linearly, not squared, so it does not hold back the many quads a
        // few millimetres off.
        const double huber = kHuberTolerances * params.planarity_tolerance;
        const double w = std::abs(dist) > huber ? std::sqrt(huber / std::abs(dist)) : 1.0;
        c(static_cast<Eigen::Index>(qi)) = w * dist;
        const double ws = w / scale;
        const std::array<Vec3, 4> grad{(-nrm - d2.cross(a)) * ws, (nrm - a.cross(d1)) * ws,
                                       d2.cross(a) * ws, a.cross(d1) * ws};
        for (int i = 0; i < 4; ++i) {
          const int k = index[static_cast<std::size_t>(q[i])];
          if (k < 0) continue;
          for (int d = 0; d < 3; ++d)
            jt.emplace_back(static_cast<int>(qi), 3 * k + d, grad[static_cast<std::size_t>(i)][d]);
        }
      }
      Sparse j(static_cast<Eigen::Index>(quads.size()), dim);
      j.setFromTriplets(jt.begin(), jt.end());
      Eigen::VectorXd x(dim), band(dim);
      for (std::size_t k = 0; k < n; ++k) {
        const std::size_t v = static_cast<std::size_t>(free[k]);
        x.segment<3>(static_cast<Eigen::Index>(3 * k)) = out.xyz[v];
        Vec3 b = out.xyz[v];
        const Vec3 off = b - foot[k].point;
        if (off.norm() > params.max_deviation)
          b = foot[k].point + off * (params.max_deviation / off.norm());
        band.segment<3>(static_cast<Eigen::Index>(3 * k)) = b;
      }
      Sparse m = Sparse(j.transpose() * j) + params.fairness * ltl;
      for (Eigen::Index i = 0; i < dim; ++i) m.coeffRef(i, i) += params.closeness + kDamping;
      // A sliding node moves along its trim's tangent: a stiff penalty on
      // the rest of its move (it is put exactly back onto the trim after).
      for (std::size_t k = 0; k < n; ++k) {
        const TrimSlider& sl = slider[static_cast<std::size_t>(free[k])];
        if (sl.loop < 0) continue;
        const Eigen::Matrix3d across =
            kSlideStiffness * (Eigen::Matrix3d::Identity() - sl.tangent * sl.tangent.transpose());
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b)
            m.coeffRef(static_cast<Eigen::Index>(3 * k + a),
                       static_cast<Eigen::Index>(3 * k + b)) += across(a, b);
      }
      m.makeCompressed();
      const Eigen::VectorXd rhs =
          -(j.transpose() * c + params.closeness * (x - band) + params.fairness * (ltl * (x - x0)));
      solver.compute(m);
      const Eigen::VectorXd dx = solver.solve(rhs);
      if (!dx.allFinite()) throw GeometryFailure("planarize: the Gauss-Newton step is not finite");
      for (std::size_t k = 0; k < n; ++k) {
        const std::size_t v = static_cast<std::size_t>(free[k]);
        const TrimSlider& sl = slider[v];
        if (sl.loop >= 0) {
          // Along the trim, at most a quarter of its shorter boundary side
          // (no node passes its neighbour), then exactly onto the trim.
          const double along =
              std::clamp(Vec3(dx.segment<3>(static_cast<Eigen::Index>(3 * k))).dot(sl.tangent),
                         -sl.reach, sl.reach);
          const Projection at = face.project(out.xyz[v] + along * sl.tangent, out.uv[v]);
          const Vec2 uv = face.snap_to_trim(sl.loop, at.uv);
          out.uv[v] = uv;
          out.xyz[v] = face.point(uv.x(), uv.y());
          foot[k].uv = uv, foot[k].point = out.xyz[v], foot[k].distance = 0;
          continue;
        }
        out.xyz[v] += dx.segment<3>(static_cast<Eigen::Index>(3 * k));
        if (params.closeness > 0) {
          // The band is a hard target: back onto its edge along the line to
          // the node's closest surface point.
          // Moved along the line to its foot, the node keeps that foot: the
          // next measure needs no second projection.
          foot[k] = face.project(out.xyz[v], foot[k].uv);
          const Vec3 off = out.xyz[v] - foot[k].point;
          if (off.norm() > params.max_deviation) {
            out.xyz[v] = foot[k].point + off * (params.max_deviation / off.norm());
            foot[k].distance = params.max_deviation;
          }
        }
      }
      int planar = 0;
      double worst = 0, far = 0;
      measure(planar, worst, far, params.closeness > 0);
      for (std::size_t k = 0; k < n; ++k)
        if (slider[static_cast<std::size_t>(free[k])].loop < 0)
          out.uv[static_cast<std::size_t>(free[k])] = foot[k].uv;
      if (planar == rep.quads && far <= params.max_deviation) {
        best = out;
        break;
      }
      // The best round so far: most quads planar, then the smallest worst one
      // (the band's hard projection can undo a step's gains).
      if (planar > best_planar || (planar == best_planar && worst < best_worst)) {
        best = out, best_planar = planar, best_worst = worst, since_best = 0;
      } else if (++since_best >= kPatience) {
        break;
      }
      best_by_round.push_back(best_planar);
      if (round >= kPatience &&
          best_planar - best_by_round[static_cast<std::size_t>(round - kPatience)] <
              std::max(1.0, kPlateauShare * rep.quads))
        break;
    }
    out = std::move(best);
  }
  measure(rep.planar_after, rep.max_planarity_after, rep.max_node_deviation_after);
  for (std::size_t v = 0; v < nv; ++v)
    rep.max_move = std::max(rep.max_move, (out.xyz[v] - mesh.xyz[v]).norm());
  rep.converged =
      rep.planar_after == rep.quads && rep.max_node_deviation_after <= params.max_deviation;
  rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (report) *report = rep;
  return out;
}

}  // namespace tessella
