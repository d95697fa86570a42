#include "tessella/surface_face.h"

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Curve2d.hxx>
#include <BRepBndLib.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GCPnts_QuasiUniformDeflection.hxx>
#include <Geom2d_Curve.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_Surface.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <TopoDS_Wire.hxx>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <optional>

#include "geometry/brep_string.h"
#include "geometry/closed_bspline.h"
#include "geometry/face_area.h"
#include "geometry/pcurve_projection.h"
#include "geometry/second_derivative_bounds.h"
#include "geometry/span_adaptors.h"
#include "geometry/span_polynomials.h"
#include "geometry/surface_sample_grid.h"
#include "tessella/errors.h"

namespace tessella {

namespace {

// What a FastEvaluation scope evaluates with: the surface (for a worker
// thread its own copy: nothing mutable shared with other threads), our span
// polynomials (B-spline / Bezier) or else OCCT's adaptors caching them.
struct Objects {
  Handle(Geom_Surface) surface;
  std::unique_ptr<SpanPolynomials> poly;  // null: the surface is not one it handles
  SpanAdaptors adaptor;
  // Evaluations counted here and added to the face's counter when the scope
  // ends, so the threads do not contend for one atomic on every evaluation.
  std::uint64_t evaluations = 0;
  // The enclosing scope of the same face on this thread, if any: evaluations()
  // counts what every open scope holds.
  Objects* outer = nullptr;
  Objects(const Handle(Geom_Surface) & s, bool copy)
      : surface(copy ? Handle(Geom_Surface)::DownCast(s->Copy()) : s),
        poly(SpanPolynomials::create(surface)),
        adaptor(surface) {}
};

// The FastEvaluation scope active on this thread: which face (its Impl) and its objects.
struct FastScope {
  const void* impl = nullptr;
  Objects* objects = nullptr;
};
thread_local FastScope tls_fast;

Vec3 to_vec(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }
Vec3 to_vec(const gp_Vec& v) { return {v.X(), v.Y(), v.Z()}; }

double signed_area(const std::vector<Vec2>& poly) {
  double a = 0;
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) {
    const Vec2& p = poly[i];
    const Vec2& q = poly[(i + 1) % n];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

}  // namespace

struct SurfaceFace::Impl {
  TopoDS_Face face;
  Handle(Geom_Surface) surface;
  UvBounds bounds;
  // Where projection may go: the face bounds grown by a margin, cut to the
  // surface's own finite bounds; periodic directions wrap instead.
  UvBounds search;
  double model_size = 0;
  double area = 0;
  bool reversed = false;
  std::unique_ptr<BRepTopAdaptor_FClass2d> classifier;
  mutable std::atomic<std::uint64_t> evaluations{0};
  mutable std::atomic<std::uint64_t> global_projections{0};
  // The global search's sample grid, built on first use from the surface
  // itself (not a scope's evaluator, so every thread gets the same samples
  // bit for bit) and then shared read-only.
  mutable std::once_flag sample_grid_once;
  // Bounds of the second derivatives (null: the surface has none), built
  // on first use and then shared read-only.
  mutable std::once_flag curvature_once;
  mutable std::unique_ptr<SecondDerivativeBounds> curvature;
  mutable std::unique_ptr<SurfaceSampleGrid> sample_grid;
  mutable std::mutex trim_mutex;
  // trim_loops' (u,v) loops (no points in space) by deflection, under trim_mutex.
  mutable std::map<double, std::vector<TrimLoop>> trim_loops_uv;
  // snap_to_trim's projections, per wire (explorer order) and edge. OCCT's
  // extrema are not thread-safe, so a set serves one call at a time: a call
  // takes one from the pool or builds one (under trim_mutex), projects
  // without the lock and gives it back. Each set projects onto copies of
  // the pcurves of its own (no OCCT object shared between threads). Calls
  // on several threads project at once (the crossings' snap was a serial
  // tenth of a trimmed dome's panelize), and every set answers as any other
  // (the same curves; each call's extrema start afresh).
  using TrimProjections = std::vector<std::vector<std::unique_ptr<PcurveProjection>>>;
  mutable std::vector<std::unique_ptr<TrimProjections>> trim_projection_pool;
  std::unique_ptr<TrimProjections> new_trim_projections() const {
    auto set = std::make_unique<TrimProjections>();
    for (TopExp_Explorer wx(face, TopAbs_WIRE); wx.More(); wx.Next()) {
      set->emplace_back();
      for (TopExp_Explorer ex(wx.Current(), TopAbs_EDGE); ex.More(); ex.Next()) {
        double first = 0, last = 0;
        const Handle(Geom2d_Curve) c =
            BRep_Tool::CurveOnSurface(TopoDS::Edge(ex.Current()), face, first, last);
        if (c.IsNull()) continue;
        const Handle(Geom2d_Curve) own = Handle(Geom2d_Curve)::DownCast(c->Copy());
        set->back().push_back(std::make_unique<PcurveProjection>(own, first, last));
      }
    }
    return set;
  }
  // Counts n evaluations into the scope o (scope()'s answer: looked up once
  // by the caller, a thread-local read in a shared library being a call).
  void count(Objects* o, std::uint64_t n = 1) const {
    if (o)
      o->evaluations += n;
    else
      evaluations.fetch_add(n, std::memory_order_relaxed);
  }
  // The objects of a FastEvaluation of this face on this thread, or null.
  Objects* scope() const { return tls_fast.impl == this ? tls_fast.objects : nullptr; }
  // One evaluation of S and its first and second derivatives (counted).
  void d2(double u, double v, Vec3& p, Vec3& su, Vec3& sv, Vec3& suu, Vec3& svv, Vec3& suv) const {
    Objects* o = scope();
    count(o);
    if (o && o->poly) {
      o->poly->d2(u, v, p.data(), su.data(), sv.data(), suu.data(), svv.data(), suv.data());
      return;
    }
    gp_Pnt P;
    gp_Vec Su, Sv, Suu, Svv, Suv;
    if (o)
      o->adaptor.at(u, v).D2(u, v, P, Su, Sv, Suu, Svv, Suv);
    else
      surface->D2(u, v, P, Su, Sv, Suu, Svv, Suv);
    p = to_vec(P), su = to_vec(Su), sv = to_vec(Sv);
    suu = to_vec(Suu), svv = to_vec(Svv), suv = to_vec(Suv);
  }

  // The surface's periodicity, read once (OCCT's virtual calls were asked
  // on every Newton step and cell bound).
  bool u_periodic = false, v_periodic = false;
  double u_period = 0, v_period = 0;
  void read_periods() {
    u_periodic = surface->IsUPeriodic();
    v_periodic = surface->IsVPeriodic();
    u_period = u_periodic ? surface->UPeriod() : 0.0;
    v_period = v_periodic ? surface->VPeriod() : 0.0;
  }

  double wrap_u(double u) const {
    if (!u_periodic) return std::clamp(u, search.u_min, search.u_max);
    const double p = u_period;
    const double lo = bounds.u_min;
    return lo + std::fmod(std::fmod(u - lo, p) + p, p);
  }
  double wrap_v(double v) const {
    if (!v_periodic) return std::clamp(v, search.v_min, search.v_max);
    const double p = v_period;
    const double lo = bounds.v_min;
    return lo + std::fmod(std::fmod(v - lo, p) + p, p);
  }
};

SurfaceFace::SurfaceFace(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
SurfaceFace::SurfaceFace(SurfaceFace&&) noexcept = default;
SurfaceFace& SurfaceFace::operator=(SurfaceFace&&) noexcept = default;
SurfaceFace::~SurfaceFace() = default;

SurfaceFace SurfaceFace::from_brep_string(const std::string& brep) {
  const TopoDS_Shape shape = shape_from_brep_string(brep);
  int face_count = 0;
  TopoDS_Face face;
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
    ++face_count;
    face = TopoDS::Face(ex.Current());
  }
  if (face_count == 0) throw InvalidGeometry("the shape has no face: select a face");
  if (face_count > 1) {
    throw InvalidGeometry("the shape has " + std::to_string(face_count) +
                          " faces: pass exactly one face");
  }
  return from_occt_face(face);
}

SurfaceFace SurfaceFace::from_occt_face(const TopoDS_Face& face) {
  auto impl = std::make_unique<Impl>();
  try {
    impl->face = face;
    impl->surface = BRep_Tool::Surface(face);  // location applied
    if (impl->surface.IsNull()) throw InvalidGeometry("the face has no surface");
    // A rectangular trim of a periodic surface (a face set's sewn cones of
    // OCCT's CrankArm.brep: a cone trimmed to one whole turn) has the same
    // points at the same (u,v) but is not periodic, so its seam was read as
    // two sides of the face: its basis is taken (the face's wires bound it).
    for (Handle(Geom_RectangularTrimmedSurface)
             t = Handle(Geom_RectangularTrimmedSurface)::DownCast(impl->surface);
         !t.IsNull() && (t->BasisSurface()->IsUPeriodic() || t->BasisSurface()->IsVPeriodic());
         t = Handle(Geom_RectangularTrimmedSurface)::DownCast(impl->surface))
      impl->surface = t->BasisSurface();
    // A B-spline surface closed on itself but not periodic: the same points
    // at the same (u,v), read as periodic (a copy; the face keeps its own).
    if (auto b = Handle(Geom_BSplineSurface)::DownCast(impl->surface))
      impl->surface = periodic_where_closed(b);
    impl->read_periods();
    impl->reversed = face.Orientation() == TopAbs_REVERSED;
    BRepTools::UVBounds(face, impl->bounds.u_min, impl->bounds.u_max, impl->bounds.v_min,
                        impl->bounds.v_max);
    Bnd_Box box;
    BRepBndLib::Add(face, box);
    if (box.IsVoid()) throw InvalidGeometry("the face has no extent");
    double x0, y0, z0, x1, y1, z1;
    box.Get(x0, y0, z0, x1, y1, z1);
    impl->model_size =
        std::sqrt((x1 - x0) * (x1 - x0) + (y1 - y0) * (y1 - y0) + (z1 - z0) * (z1 - z0));
    impl->area = face_area(face);
  } catch (const Standard_Failure& e) {
    throw InvalidGeometry(std::string("the face cannot be evaluated: ") + e.GetMessageString());
  }
  const UvBounds& b = impl->bounds;
  const double du = b.u_max - b.u_min, dv = b.v_max - b.v_min;
  if (!std::isfinite(du) || !std::isfinite(dv))
    throw InvalidGeometry("the face is degenerate: its parameter range is infinite");
  if (!(du > 0) || !(dv > 0))
    throw FaceWithoutArea("the face is degenerate: its parameter range is empty");
  if (!std::isfinite(impl->model_size))
    throw InvalidGeometry("the face is degenerate: it has no finite extent");
  if (!(impl->model_size > 0) || !(impl->area > 1e-12 * impl->model_size * impl->model_size))
    throw FaceWithoutArea("the face is degenerate: it has no area");
  double su0, su1, sv0, sv1;
  impl->surface->Bounds(su0, su1, sv0, sv1);
  impl->search = {std::max(su0, b.u_min - 0.1 * du), std::min(su1, b.u_max + 0.1 * du),
                  std::max(sv0, b.v_min - 0.1 * dv), std::min(sv1, b.v_max + 0.1 * dv)};
  // Tolerance of the uv classifier: a tiny fraction of the parameter span.
  impl->classifier = std::make_unique<BRepTopAdaptor_FClass2d>(face, 1e-9 * std::max(du, dv));
  return SurfaceFace(std::move(impl));
}

UvBounds SurfaceFace::bounds() const { return impl_->bounds; }
UvBounds SurfaceFace::search_bounds() const { return impl_->search; }

bool SurfaceFace::second_derivative_bound(const UvBounds& box, SecondDerivativeBound& out) const {
  const Impl& s = *impl_;
  std::call_once(s.curvature_once,
                 [&s] { s.curvature = SecondDerivativeBounds::create(s.surface); });
  if (!s.curvature) return false;
  out = s.curvature->over(box);
  return true;
}
double SurfaceFace::model_size() const { return impl_->model_size; }
bool SurfaceFace::u_periodic() const { return impl_->u_periodic; }
bool SurfaceFace::v_periodic() const { return impl_->v_periodic; }
double SurfaceFace::u_period() const { return impl_->u_period; }
double SurfaceFace::v_period() const { return impl_->v_period; }
bool SurfaceFace::reversed() const { return impl_->reversed; }
double SurfaceFace::area() const { return impl_->area; }

Vec3 SurfaceFace::point(double u, double v) const {
  Objects* o = impl_->scope();
  impl_->count(o);
  if (o) {
    if (!o->poly) return to_vec(o->adaptor.at(u, v).Value(u, v));
    Vec3 p;
    o->poly->d0(u, v, p.data());
    return p;
  }
  return to_vec(impl_->surface->Value(u, v));
}

struct SurfaceFace::FastEvaluation::State {
  FastScope previous;
  Objects objects;
  State(const Handle(Geom_Surface) & s, bool copy) : objects(s, copy) {}
};

bool SurfaceFace::FastEvaluation::active(const SurfaceFace& face) {
  return tls_fast.impl == face.impl_.get();
}

SurfaceFace::FastEvaluation::FastEvaluation(const SurfaceFace& face, bool own_surface)
    : state_(std::make_unique<State>(face.impl_->surface, own_surface)) {
  state_->previous = tls_fast;
  if (tls_fast.impl == face.impl_.get()) state_->objects.outer = tls_fast.objects;
  tls_fast = {face.impl_.get(), &state_->objects};
}

SurfaceFace::FastEvaluation::~FastEvaluation() {
  static_cast<const Impl*>(tls_fast.impl)
      ->evaluations.fetch_add(state_->objects.evaluations, std::memory_order_relaxed);
  tls_fast = state_->previous;
}

std::uint64_t SurfaceFace::evaluations() const {
  std::uint64_t n = impl_->evaluations.load(std::memory_order_relaxed);
  for (const Objects* o = impl_->scope(); o; o = o->outer) n += o->evaluations;
  return n;
}
void SurfaceFace::reset_evaluations() const {
  impl_->evaluations.store(0, std::memory_order_relaxed);
  for (Objects* o = impl_->scope(); o; o = o->outer) o->evaluations = 0;
}

std::uint64_t SurfaceFace::global_projections() const {
  return impl_->global_projections.load(std::memory_order_relaxed);
}
void SurfaceFace::reset_global_projections() const {
  impl_->global_projections.store(0, std::memory_order_relaxed);
}

SurfacePoint SurfaceFace::derivatives(double u, double v) const {
  Objects* o = impl_->scope();
  impl_->count(o);
  if (o && o->poly) {
    SurfacePoint d;
    o->poly->d1(u, v, d.point.data(), d.du.data(), d.dv.data());
    return d;
  }
  gp_Pnt p;
  gp_Vec du, dv;
  if (o)
    o->adaptor.at(u, v).D1(u, v, p, du, dv);
  else
    impl_->surface->D1(u, v, p, du, dv);
  return {to_vec(p), to_vec(du), to_vec(dv)};
}

Vec3 SurfaceFace::normal(double u, double v) const {
  const UvBounds& b = impl_->bounds;
  const double sign = impl_->reversed ? -1.0 : 1.0;
  // At a pole du x dv vanishes: step towards the middle of the face until the
  // normal is defined (the limit normal of the pole).
  for (double t : {0.0, 1e-7, 1e-5, 1e-3}) {
    const double uu = u + t * (0.5 * (b.u_min + b.u_max) - u);
    const double vv = v + t * (0.5 * (b.v_min + b.v_max) - v);
    const SurfacePoint d = derivatives(uu, vv);
    const Vec3 n = d.du.cross(d.dv);
    const double scale = d.du.norm() * d.dv.norm();
    if (n.norm() > 1e-12 * scale && n.norm() > 0) return sign * n.normalized();
  }
  throw GeometryFailure("the surface normal is undefined near (" + std::to_string(u) + ", " +
                        std::to_string(v) + ")");
}

bool SurfaceFace::is_inside(double u, double v) const {
  return impl_->classifier->Perform(gp_Pnt2d(u, v)) != TopAbs_OUT;
}

Vec2 SurfaceFace::snap_to_trim(int loop, const Vec2& uv) const {
  const Impl& s = *impl_;
  int wire = 0;
  std::unique_ptr<Impl::TrimProjections> set;
  {
    const std::lock_guard<std::mutex> lock(s.trim_mutex);
    // `loop` counts in trim_loops' order (the outer loop first, then the
    // holes, degenerate wires left out), not the B-rep's: a face whose outer
    // wire is not its first (an annulus of a STEP part, its hole listed
    // first) snapped the grid's crossings with the outer circle onto the hole
    // and left 0.4-1.8% of the face uncovered. The loops' wires are the same
    // at any deflection.
    if (s.trim_loops_uv.empty()) {
      const std::vector<TrimLoop> loops = trim_loops_uv(1e-3 * s.model_size);
      s.trim_loops_uv.emplace(1e-3 * s.model_size, loops);
    }
    const std::vector<TrimLoop>& loops = s.trim_loops_uv.begin()->second;
    require_in_range("trim loop index", loop, 0, static_cast<int>(loops.size()) - 1);
    wire = loops[static_cast<std::size_t>(loop)].wire;
    if (s.trim_projection_pool.empty()) {
      set = s.new_trim_projections();
    } else {
      set = std::move(s.trim_projection_pool.back());
      s.trim_projection_pool.pop_back();
    }
  }
  Vec2 best = uv;
  double best_d = std::numeric_limits<double>::infinity();
  const gp_Pnt2d p(uv.x(), uv.y());
  std::vector<gp_Pnt2d> candidates;
  for (const auto& edge : (*set)[static_cast<std::size_t>(wire)]) {
    // An edge whose every point is farther than the nearest candidate so
    // far cannot change the answer (its candidates are never strictly
    // nearer): not projected (a loop of many edges projected each crossing
    // onto every one of them).
    if (edge->lower_bound(p) > best_d) continue;
    edge->candidates(p, candidates);
    for (const gp_Pnt2d& q : candidates) {
      const double d = q.Distance(p);
      if (d < best_d) best_d = d, best = Vec2(q.X(), q.Y());
    }
  }
  const std::lock_guard<std::mutex> lock(s.trim_mutex);
  s.trim_projection_pool.push_back(std::move(set));
  return best;
}

std::vector<TrimLoop> SurfaceFace::trim_loops(double deflection) const {
  require_in_range("trim deflection", deflection, 1e-12 * impl_->model_size, impl_->model_size);
  // The loops in (u,v) come from OCCT's sampling of the edges alone, the same
  // for every call: kept per deflection (the pipeline's stages asked for the
  // same loops several times, 2-3% of panelize). Their points in space are
  // evaluated on each call, in the caller's evaluation scope, as before.
  std::vector<TrimLoop> loops;
  bool known = false;
  {
    const std::lock_guard<std::mutex> lock(impl_->trim_mutex);
    const auto it = impl_->trim_loops_uv.find(deflection);
    if (it != impl_->trim_loops_uv.end()) loops = it->second, known = true;
  }
  if (!known) {
    loops = trim_loops_uv(deflection);
    const std::lock_guard<std::mutex> lock(impl_->trim_mutex);
    if (impl_->trim_loops_uv.size() >= 16) impl_->trim_loops_uv.clear();  // a bound, rarely hit
    impl_->trim_loops_uv.emplace(deflection, loops);
  }
  for (TrimLoop& loop : loops) {
    loop.xyz.reserve(loop.uv.size());
    for (const Vec2& q : loop.uv) loop.xyz.push_back(point(q.x(), q.y()));
  }
  return loops;
}

std::vector<TrimLoop> SurfaceFace::trim_loops_uv(double deflection) const {
  const TopoDS_Wire outer = BRepTools::OuterWire(impl_->face);
  std::vector<TrimLoop> loops;
  try {
    int wire_index = 0;
    for (TopExp_Explorer wx(impl_->face, TopAbs_WIRE); wx.More(); wx.Next(), ++wire_index) {
      const TopoDS_Wire wire = TopoDS::Wire(wx.Current());
      TrimLoop loop;
      loop.outer = wire.IsSame(outer);
      loop.wire = wire_index;
      double closing_tolerance = 0;  // of the vertex the wire starts and ends at
      for (BRepTools_WireExplorer ex(wire, impl_->face); ex.More(); ex.Next()) {
        const TopoDS_Edge& edge = ex.Current();
        if (loop.uv.empty() && !ex.CurrentVertex().IsNull())
          closing_tolerance = BRep_Tool::Tolerance(ex.CurrentVertex());
        BRepAdaptor_Curve2d pcurve(edge, impl_->face);
        std::vector<double> params;
        if (BRep_Tool::Degenerated(edge)) {
          // A pole: the edge has no length in 3D but spans uv; a few uv points
          // keep the loop closed in the parameter plane.
          for (int i = 0; i <= 8; ++i) {
            params.push_back(pcurve.FirstParameter() +
                             (pcurve.LastParameter() - pcurve.FirstParameter()) * i / 8.0);
          }
        } else {
          BRepAdaptor_Curve curve(edge);
          // Sampled span by span: on a closed edge (one edge making a whole
          // loop) the sampler sees equal end points and may return just them.
          const int spans = 8;
          const double t0 = curve.FirstParameter(), t1 = curve.LastParameter();
          params.push_back(t0);
          for (int k = 0; k < spans; ++k) {
            const double a = t0 + (t1 - t0) * k / spans, b = t0 + (t1 - t0) * (k + 1) / spans;
            GCPnts_QuasiUniformDeflection sampler(curve, deflection, a, b);
            if (!sampler.IsDone() || sampler.NbPoints() < 2) {
              throw GeometryFailure("cannot discretize a trim edge of the face");
            }
            for (int i = 2; i <= sampler.NbPoints(); ++i) params.push_back(sampler.Parameter(i));
          }
        }
        if (edge.Orientation() == TopAbs_REVERSED) std::reverse(params.begin(), params.end());
        // The first point of each edge repeats the last of the previous one,
        // which is a wire vertex (a corner of the trim).
        if (!loop.corner.empty()) loop.corner.back() = 1;
        for (std::size_t i = loop.uv.empty() ? 0 : 1; i < params.size(); ++i) {
          const gp_Pnt2d q = pcurve.Value(params[i]);
          loop.uv.emplace_back(q.X(), q.Y());
          loop.corner.push_back(i == 0 ? 1 : 0);
        }
      }
      // Drop the closing duplicate and repeated points (a dropped point passes
      // its corner flag on to the point it repeats).
      std::vector<Vec2> clean;
      std::vector<char> corner;
      const double eps = 1e-12 * std::max(impl_->bounds.u_max - impl_->bounds.u_min,
                                          impl_->bounds.v_max - impl_->bounds.v_min);
      for (std::size_t i = 0; i < loop.uv.size(); ++i) {
        if (!clean.empty() && (loop.uv[i] - clean.back()).norm() <= eps) {
          corner.back() |= loop.corner[i];
          continue;
        }
        clean.push_back(loop.uv[i]);
        corner.push_back(loop.corner[i]);
      }
      bool closed = false;
      while (clean.size() > 1 && (clean.front() - clean.back()).norm() <= eps) {
        corner.front() |= corner.back();
        clean.pop_back();
        corner.pop_back();
        closed = true;
      }
      // The last edge ends at the vertex the first one starts at, as every
      // edge starts at its previous one's end (that repeat is dropped above,
      // however far its pcurve ends): a wire may close with a gap within its
      // vertex's tolerance (a STEP diode's face, 3.8e-7 mm; the roof cut
      // along its diagonals, 1.7e-4 mm), which kept made a rod or a panel
      // side of that length at the corner. Dropped within the tolerance
      // (twice: two points in its sphere), never beyond 1e-3 of the model;
      // a gap under 1e-9 of the model is left (the meshes weld such points,
      // and the cuts near them stay as they were).
      if (!closed && clean.size() > 3) {
        const double gap = (point(clean.front().x(), clean.front().y()) -
                            point(clean.back().x(), clean.back().y()))
                               .norm();
        const double within = std::min(std::max(2 * closing_tolerance, 1e-6 * impl_->model_size),
                                       1e-3 * impl_->model_size);
        if (gap > 1e-9 * impl_->model_size && gap <= within) {
          corner.front() |= corner.back();
          clean.pop_back();
          corner.pop_back();
        }
      }
      if (clean.size() < 3) continue;
      const double a = signed_area(clean);
      if ((loop.outer && a < 0) || (!loop.outer && a > 0)) {
        std::reverse(clean.begin(), clean.end());
        std::reverse(corner.begin(), corner.end());
      }
      loop.uv = std::move(clean);
      loop.corner = std::move(corner);
      loops.push_back(std::move(loop));
    }
  } catch (const Standard_Failure& e) {
    throw GeometryFailure(std::string("cannot discretize the trim loops: ") + e.GetMessageString());
  }
  if (std::none_of(loops.begin(), loops.end(), [](const TrimLoop& l) { return l.outer; })) {
    throw GeometryFailure("the outer boundary of the face could not be discretized");
  }
  // Outer loop first, then holes in the order of the B-rep.
  std::stable_sort(loops.begin(), loops.end(),
                   [](const TrimLoop& a, const TrimLoop& b) { return a.outer && !b.outer; });
  return loops;
}

namespace {

// Newton iteration of seed 004 section 4 (eq. 10-18) from (u, v); true with
// (u, v) a foot point (an orthogonal minimum of the distance), false where it
// does not converge, stops at a maximum or saddle, or stalls at a pole.
// `at` gets S(u, v) when the last evaluation was at the final (u, v) (the
// caller then needs no evaluation of its own), else it is left empty.
template <class Impl>
bool newton_foot(const Impl& s, const Vec3& p, double& u, double& v, const ProjectionParams& params,
                 std::optional<Vec3>* at = nullptr) {
  const double eps1 = params.distance_tolerance * s.model_size;
  bool converged = false;
  for (int it = 0; it <= params.max_iterations; ++it) {
    Vec3 P, su, sv, suu, svv, suv;
    s.d2(u, v, P, su, sv, suu, svv, suv);
    const Vec3 r = P - p;
    const double rn = r.norm();
    // Eq. 12-14: J is the Hessian of |r|^2 / 2, kappa its gradient.
    const double f = r.dot(su), g = r.dot(sv);
    const double a = su.squaredNorm() + r.dot(suu);
    const double b = su.dot(sv) + r.dot(suv);
    const double d = sv.squaredNorm() + r.dot(svv);
    const double det = a * d - b * b;
    if (at) *at = P;
    if (rn <= eps1) {
      converged = true;  // p lies on the surface
      break;
    }
    // Eq. 18: r orthogonal to both tangents. Newton also stops on maxima and
    // saddles of the distance, so a foot point must be a minimum (J positive
    // definite); a pole (a tangent vanishes) is left to the fallback.
    const double tol = params.orthogonality_tolerance * rn;
    if (su.norm() > 0 && sv.norm() > 0 && std::abs(f) <= tol * su.norm() &&
        std::abs(g) <= tol * sv.norm()) {
      converged = a > 0 && det > 0;
      break;
    }
    if (it == params.max_iterations || !(std::abs(det) > 1e-300) || !std::isfinite(det)) break;
    // Eq. 15-16: J delta = -kappa, then step.
    const double du = -(d * f - b * g) / det;
    const double dv = -(a * g - b * f) / det;
    const double nu = s.wrap_u(u + du), nv = s.wrap_v(v + dv);
    // Eq. 17 in 3D: a step that no longer moves the point ends the iteration
    // (clamped at the border of the search range, or stalled).
    const double step3d = (su * (nu - u) + sv * (nv - v)).norm();
    u = nu;
    v = nv;
    if (at) at->reset();  // (u, v) moved after the evaluation
    if (step3d <= eps1) {
      // Newton's step has vanished: a foot point if it is a minimum and not a
      // pole (where a vanishing tangent also makes every step short).
      const double t = std::min(su.norm(), sv.norm()) / std::max(su.norm(), sv.norm());
      converged = a > 0 && det > 0 && t > 1e-6;
      break;
    }
  }
  return converged;
}

}  // namespace

Projection SurfaceFace::project(const Vec3& p, const Vec2& start,
                                const ProjectionParams& params) const {
  const Impl& s = *impl_;
  double u = s.wrap_u(start.x()), v = s.wrap_v(start.y());
  std::optional<Vec3> at;
  bool converged = newton_foot(s, p, u, v, params, &at);
  if (!converged && params.local_search) {
    // Before the global search (100 ms a call on a 312 x 323-pole surface):
    // Newton again from the nearest of 9 x 9 samples around the start, over
    // the parameter box that (to first order in the start's tangents) holds
    // every surface point within twice the start's distance, the foot point
    // among them. Kept only if it is no farther than the nearest sample.
    const double u0 = s.wrap_u(start.x()), v0 = s.wrap_v(start.y());
    const SurfacePoint sp = derivatives(u0, v0);
    const double reach = 2.0 * (sp.point - p).norm();
    const double su = sp.du.norm(), sv = sp.dv.norm();
    if (su > 0 && sv > 0 && reach > 0) {
      const double ru = std::min(reach / su, s.search.u_max - s.search.u_min);
      const double rv = std::min(reach / sv, s.search.v_max - s.search.v_min);
      double best = std::numeric_limits<double>::infinity();
      const int n = 4;
      for (int i = -n; i <= n; ++i) {
        for (int j = -n; j <= n; ++j) {
          const double a = s.wrap_u(u0 + ru * i / n), b = s.wrap_v(v0 + rv * j / n);
          const double d = (point(a, b) - p).norm();
          if (d < best) best = d, u = a, v = b;
        }
      }
      converged = newton_foot(s, p, u, v, params, &at) && (point(u, v) - p).norm() <= best;
    }
  }
  Projection result;
  if (converged) {
    result.uv = {u, v};
    result.point = at ? *at : point(u, v);
    result.distance = (result.point - p).norm();
    return result;
  }
  if (!params.global_search) {
    result.uv = {u, v};
    result.point = point(u, v);
    result.distance = std::numeric_limits<double>::infinity();
    result.used_fallback = true;
    return result;
  }
  result = project(p);
  result.used_fallback = true;
  return result;
}

namespace {

// Samples per direction of the global search's grid: 4 per knot span of a
// B-spline inside the search range (a foot point's basin is at least a
// fraction of a span wide), at least 32; 64 for other surfaces.
// Until stop 43 each direction was capped at 512 samples: on OCCT's terrain
// (309 x 320 spans of 25 mm) the step became 15 mm, wider than the steep
// dips of its border spans, and the search returned 14.13 mm where the
// surface passes 7.70 mm away. Only the total is capped now
// (kMaxGlobalSamples, 100 MB of points), for surfaces of more than about
// 250,000 spans, where the density per span falls below 4 evenly in both
// directions.
constexpr double kMaxGlobalSamples = 4.0 * 1024 * 1024;

std::pair<int, int> sample_counts(const Handle(Geom_Surface) & surface, const UvBounds& range) {
  int nu = 64, nv = 64;
  if (auto b = Handle(Geom_BSplineSurface)::DownCast(surface)) {
    auto spans = [](const TColStd_Array1OfReal& knots, double lo, double hi) {
      int n = 0;
      for (int k = knots.Lower(); k < knots.Upper(); ++k)
        if (knots(k + 1) > lo && knots(k) < hi) ++n;
      return std::max(1, n);
    };
    nu = std::max(32, 4 * spans(b->UKnots(), range.u_min, range.u_max));
    nv = std::max(32, 4 * spans(b->VKnots(), range.v_min, range.v_max));
    const double total = double(nu + 1) * double(nv + 1);
    if (total > kMaxGlobalSamples) {
      const double f = std::sqrt(kMaxGlobalSamples / total);
      nu = std::max(32, int(nu * f));
      nv = std::max(32, int(nv * f));
    }
  }
  return {nu, nv};
}

}  // namespace

Projection SurfaceFace::project(const Vec3& p) const {
  const Impl& s = *impl_;
  s.global_projections.fetch_add(1, std::memory_order_relaxed);
  std::call_once(s.sample_grid_once, [&s] {
    const auto [nu, nv] = sample_counts(s.surface, s.search);
    s.sample_grid = std::make_unique<SurfaceSampleGrid>(
        s.search, nu, nv, [&s](double u, double v) { return to_vec(s.surface->Value(u, v)); });
  });
  const SurfaceSampleGrid& grid = *s.sample_grid;
  // From each candidate sample: Newton to the foot point of its basin, kept
  // if no farther than the sample; where it fails (the closest point lies on
  // the border of the search range, or at a pole) and from every sample on
  // the border, a pattern search in (u,v), clamped to
  // the range, halving its step until it is below 1e-12 of the range. The
  // nearest of these answers.
  const double stop_u = 1e-12 * (s.search.u_max - s.search.u_min);
  const double stop_v = 1e-12 * (s.search.v_max - s.search.v_min);
  Projection result;
  result.distance = std::numeric_limits<double>::infinity();
  for (const SurfaceSampleGrid::Sample& start : grid.candidates(p, 8)) {
    double u = start.uv.x(), v = start.uv.y();
    bool found = false;
    // From the sample and from the centres of the four cells around it: on a
    // surface with bumps about a grid step wide two foot points can share one
    // sample's basin (MAT.brep: the nearer 0.32 mm, Newton from the sample
    // found the other at 0.34).
    for (int c = 0; c < 5; ++c) {
      u = s.wrap_u(start.uv.x() + (c == 0 ? 0.0 : (c % 2 ? 0.5 : -0.5) * grid.step_u()));
      v = s.wrap_v(start.uv.y() + (c == 0 ? 0.0 : (c < 3 ? 0.5 : -0.5) * grid.step_v()));
      std::optional<Vec3> at;
      if (!newton_foot(s, p, u, v, ProjectionParams{}, &at)) continue;
      const Vec3 q = at ? *at : point(u, v);
      const double d = (q - p).norm();
      if (!(d <= start.distance)) continue;
      found = true;
      if (d < result.distance) result.uv = {u, v}, result.point = q, result.distance = d;
    }
    // A sample on the border of the range also stands for the border's own
    // closest point, which has no orthogonal foot.
    const bool border =
        (!s.u_periodic && (start.uv.x() == s.search.u_min || start.uv.x() == s.search.u_max)) ||
        (!s.v_periodic && (start.uv.y() == s.search.v_min || start.uv.y() == s.search.v_max));
    if (found && !border) continue;
    u = start.uv.x(), v = start.uv.y();
    double best = start.distance;
    double hu = grid.step_u(), hv = grid.step_v();
    // A neighbour that repeats one already evaluated this round (on the
    // border, u - hu clamps to u) has the same distance, which cannot be
    // below best after that one: not evaluated again. Nor the centre once
    // the search has moved (best is then the centre's own distance; before,
    // best is the sample's, which the evaluation here may beat by an ulp).
    // The same steps and answer as evaluating all eight, with 3 of 8
    // evaluations fewer along a border (OCCT's terrain: 18,000 searches from
    // border samples a panelize, 44 rounds each).
    bool moved = false;
    for (int round = 0; round < 1000 && (hu > stop_u || hv > stop_v); ++round) {
      double bu = u, bv = v;
      double seen_u[8], seen_v[8];
      int seen = 0;
      for (int i = -1; i <= 1; ++i)
        for (int j = -1; j <= 1; ++j) {
          if (i == 0 && j == 0) continue;
          const double cu = s.wrap_u(u + i * hu), cv = s.wrap_v(v + j * hv);
          if (moved && cu == u && cv == v) continue;
          bool repeat = false;
          for (int k = 0; k < seen && !repeat; ++k) repeat = seen_u[k] == cu && seen_v[k] == cv;
          if (repeat) continue;
          seen_u[seen] = cu, seen_v[seen] = cv, ++seen;
          const double d = (point(cu, cv) - p).norm();
          if (d < best) best = d, bu = cu, bv = cv;
        }
      if (bu == u && bv == v) {
        hu *= 0.5, hv *= 0.5;
      } else {
        u = bu, v = bv;
        moved = true;
      }
    }
    if (best < result.distance)
      result.uv = {u, v}, result.point = point(u, v), result.distance = best;
  }
  result.distance = (result.point - p).norm();
  return result;
}

}  // namespace tessella
