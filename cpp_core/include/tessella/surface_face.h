// SurfaceFace: read access to one trimmed face of a B-rep (any OCCT surface type:
// B-spline, Bezier, cylinder, plane, ...). Knows nothing about FreeCAD: the face
// arrives as a BRep string (BRepTools::Write format).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tessella/vec.h"

class TopoDS_Face;  // OCCT: only the core's own code builds a face from it

namespace tessella {

struct UvBounds {
  double u_min = 0, u_max = 0, v_min = 0, v_max = 0;
};

// A point of the surface with its first derivatives.
struct SurfacePoint {
  Vec3 point, du, dv;
};

// A closed trim loop: uv polyline (first point not repeated at the end), the
// matching 3D points, and whether it is the outer loop. Orientation: the face
// lies to the left in (u,v), i.e. the outer loop is counter-clockwise and holes
// are clockwise.
struct TrimLoop {
  std::vector<Vec2> uv;
  std::vector<Vec3> xyz;
  // 1 where the point is a vertex of the B-rep wire (where trim edges meet).
  std::vector<char> corner;
  bool outer = false;
  int wire = -1;  // the B-rep wire it samples (the face's wires in explorer order)
};

// Upper bounds of the second derivatives' norms |S_uu|, |S_uv|, |S_vv|.
struct SecondDerivativeBound {
  double uu = 0, uv = 0, vv = 0;
};

struct ProjectionParams {
  double distance_tolerance = 1e-9;        // eps1 of seed 004 eq. 18, relative to model size
  double orthogonality_tolerance = 1e-10;  // eps2 of seed 004 eq. 18 (cosine)
  int max_iterations = 30;
  // Where Newton fails, try again from the nearest of a local sample around
  // the start before the costly global search (the metrics use it).
  bool local_search = false;
  // Where Newton (and the local search) fail: OCCT's global search (true), or
  // a result with an infinite distance, for a caller that holds an upper
  // bound of its own (100 ms a call on a 312 x 323-pole surface).
  bool global_search = true;
};

struct Projection {
  Vec2 uv;
  Vec3 point;
  double distance = 0;
  bool used_fallback = false;  // Newton failed; OCCT's Extrema answered
};

class SurfaceFace {
 public:
  // Throws InvalidGeometry if the string holds no face, more than one face,
  // or a face without area.
  static SurfaceFace from_brep_string(const std::string& brep);
  // The same from an OCCT face (a face of a face set, already parsed).
  static SurfaceFace from_occt_face(const TopoDS_Face& face);

  SurfaceFace(SurfaceFace&&) noexcept;
  SurfaceFace& operator=(SurfaceFace&&) noexcept;
  ~SurfaceFace();

  // Bounds of the trimmed face in (u,v) (not of the underlying surface).
  UvBounds bounds() const;
  // The (u,v) range project() searches: bounds() widened by 10% each way,
  // within the surface's own bounds. A foot point on its border need not be
  // orthogonal (the nearest point of the range lies on its border).
  UvBounds search_bounds() const;
  // Diagonal of the face's 3D bounding box: the length tolerances scale with it.
  double model_size() const;
  bool u_periodic() const;
  bool v_periodic() const;
  double u_period() const;
  double v_period() const;
  // The face's orientation flips its normal relative to du x dv.
  bool reversed() const;

  Vec3 point(double u, double v) const;
  SurfacePoint derivatives(double u, double v) const;
  // Unit normal of the face (orientation included); falls back to a
  // neighbouring point at a degenerate pole.
  Vec3 normal(double u, double v) const;

  // Whether (u,v) lies inside the trimmed face (on the boundary counts as inside).
  bool is_inside(double u, double v) const;

  // The trim loops as polylines whose chords stay within `deflection` (mm) of
  // the true 3D trim curves. Seam edges and degenerate edges are kept in uv so
  // the loops close in the parameter plane.
  std::vector<TrimLoop> trim_loops(double deflection) const;

  // The point of trim loop `loop` (trim_loops order) closest in (u,v) to `uv`,
  // taken on the edges' own curves on the surface (pcurves), so it lies on the
  // true trim, not on a polyline chord. Throws InvalidParameter for a bad loop.
  Vec2 snap_to_trim(int loop, const Vec2& uv) const;

  // Bounds of the second derivatives valid over the whole (u,v) box, from the
  // surface's control net (B-spline, Bezier) or closed form (plane, cylinder,
  // cone, sphere, torus); false for other surfaces. Built on first use.
  bool second_derivative_bound(const UvBounds& box, SecondDerivativeBound& out) const;

  // Area of the trimmed face (OCCT's surface integral).
  double area() const;

  // Closest point of the surface to p: Newton iteration of seed 004 section 4
  // (eq. 10-18) from `start`, kept inside the parameter bounds (wrapped across a
  // periodic seam); OCCT's Extrema as a fallback when Newton does not converge
  // or stalls at a pole.
  Projection project(const Vec3& p, const Vec2& start, const ProjectionParams& params = {}) const;
  // Same, without a start: the start is found by OCCT (global search).
  Projection project(const Vec3& p) const;

  // How many times the surface was evaluated (point, derivatives, one Newton
  // step of project) since construction or the last reset: the cost measure of
  // the methods' comparison. Counted with a relaxed atomic, so a face shared
  // by threads still counts every evaluation (those of another thread's
  // FastEvaluation scope once that scope ends; this thread's open scopes at
  // once).
  std::uint64_t evaluations() const;
  void reset_evaluations() const;
  // How many projections took the global search (Newton failed): the search
  // is costly on a big surface, so this should stay a small share.
  std::uint64_t global_projections() const;
  void reset_global_projections() const;

  // While a FastEvaluation of this face lives, point(), derivatives(),
  // normal() and project() called on the same thread evaluate a non-periodic
  // B-spline / Bezier surface span by span from its Taylor polynomials
  // (SpanPolynomials: about twice as fast as OCCT's GeomAdaptor_Surface for
  // the many nearby evaluations of the agents and metrics; agrees with OCCT
  // to ~1e-13 of the model size, on knots picking the same span), other
  // surfaces through GeomAdaptor_Surface (which caches one span's polynomial).
  // The scope keeps its own span caches and global search; with
  // `own_surface` it also evaluates its own copy of the surface
  // (Geom_Surface::Copy), so a worker thread shares nothing mutable with the
  // others: each thread opens its own scope. Scopes nest. Evaluations are
  // counted in the scope and added to the face's counter when it ends.
  class FastEvaluation {
   public:
    explicit FastEvaluation(const SurfaceFace& face, bool own_surface = false);
    // Whether a scope of `face` is open on this thread.
    static bool active(const SurfaceFace& face);
    ~FastEvaluation();
    FastEvaluation(const FastEvaluation&) = delete;
    FastEvaluation& operator=(const FastEvaluation&) = delete;

   private:
    struct State;
    std::unique_ptr<State> state_;
  };

 private:
  struct Impl;
  explicit SurfaceFace(std::unique_ptr<Impl> impl);
  // trim_loops without the points in space (uv, corners, outer; sampled anew).
  std::vector<TrimLoop> trim_loops_uv(double deflection) const;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tessella
