// Private helpers of the agent methods (walking agent, gradient descent,
// relaxed grid): trim tests along rows, lockstep row agents, the 1-D walks.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "geometry/uv_trim_classifier.h"
#include "tessella/surface_face.h"
#include "tessella/vec.h"

namespace tessella::agents {

// Chord deviation of the thesis: distance between the chord midpoint and the
// surface point halfway along the walked (u,v) path.
inline double chord_deviation(const Vec3& a, const Vec3& b, const Vec3& mid) {
  return (0.5 * (a + b) - mid).norm();
}

// The same for the straight (u,v) path from qa to qb (surface points pa, pb),
// with "halfway along the path" taken in length: the thesis' agents used the
// parameter midpoint, which on an uneven parameterization lies off the middle
// of the path and adds a tangential offset to the deviation (measured: the
// agents then stop at a quarter of the bound). One secant step moves the
// parameter midpoint onto the plane through the chord midpoint normal to the
// chord, where the distance is the sagitta. Two surface evaluations.
double path_deviation(const SurfaceFace& face, const Vec2& qa, const Vec2& qb, const Vec3& pa,
                      const Vec3& pb);

// The agents' trim test: the one (u,v) classifier on the trim polylines at
// the steering deflection (trim_deflection.h: it only decides which agents and
// cells see the face; the panels are cut by clip_grid at the trim deflection).
UvTrimClassifier agent_trim(const SurfaceFace& face);

// Sorted crossings of the row {dir coordinate free, other = c} with the trim,
// c kept 1e-7 of the span off the border of the face's (u,v) bounds, where trim
// edges run along the row and the crossing count would be ambiguous.
std::vector<double> row_crossings(const SurfaceFace& face, const UvTrimClassifier& trim, int dir,
                                  double c);

// Agents on parallel rows (fixed cross parameter) walking along `dir`
// (0 = u, 1 = v) in lockstep: probe(a, b) is the largest chord deviation and
// chord length over the rows whose segment [a, b] touches the face.
class RowAgents {
 public:
  RowAgents(const SurfaceFace& face, const UvTrimClassifier& trim, int dir,
            std::vector<double> rows);
  struct Probe {
    double deviation = 0, length = 0;
  };
  Probe probe(double a, double b);
  const std::vector<double>& rows() const { return rows_; }

 private:
  bool row_inside(std::size_t r, double s) const;
  Vec3 eval(std::size_t r, double s) const;
  const SurfaceFace& face_;
  int dir_;
  std::vector<double> rows_;
  std::vector<std::vector<double>> crossings_;
  double origin_ = 0;
  bool origin_valid_ = false;
  std::vector<Vec3> origin_points_;
};

// `count` + 1 evenly spaced values from lo to hi.
std::vector<double> even_rows(double lo, double hi, int count);

// The walking agent's 1-D walk from s0 to s1 (either direction): steps of
// `step`, grows while ok(a, b), then steps back by step / 10 (halving below a
// tenth if even that breaks the rule) and places a node. Returns the nodes in
// walk order, s0 and s1 included.
std::vector<double> walk(double s0, double s1, double step,
                         const std::function<bool(double, double)>& ok);

// The gradient-descent walk (thesis 5.2 / appendix V): first step `first`,
// then step = target * (S1 + S2) / (E1 + E2), clamped to [min_step, max_step].
std::vector<double> gradient_walk(double s0, double s1, double first, double min_step,
                                  double max_step, double target,
                                  const std::function<double(double, double)>& deviation);

// Nodes from both walks of a start inside (s_start in (lo, hi)) or from one end,
// merged and sorted increasing.
std::vector<double> merge_walks(std::vector<double> a, std::vector<double> b);

// Parses a start name: corner (u_from_min, v_from_min) or max_curvature.
struct StartSpec {
  bool max_curvature = false;
  bool u_from_min = true, v_from_min = true;
};
StartSpec parse_start(const std::string& start);

// The sample node with the largest chord deviation over a u and a v chord of
// one sample step (inside the face).
Vec2 max_curvature_point(const SurfaceFace& face, const UvTrimClassifier& trim, double sample_step);

}  // namespace tessella::agents
