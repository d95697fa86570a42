// Panels from crossing curve families, closed by the trim (see the header).
#include "mesh/curve_family_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/trim_deflection.h"
#include "mesh/panel_model.h"
#include "methods/boundary_driven/bd_network.h"
#include "methods/boundary_driven/bd_refine.h"
#include "methods/boundary_driven/bd_sources.h"
#include "methods/guide_lines/guide_curves.h"
#include "tessella/errors.h"
#include "tessella/surface_face.h"

namespace tessella {

namespace {

struct TrimFoot {
  int loop = -1;
  double s = 0.0;
  double dist = std::numeric_limits<double>::infinity();
};

// Nearest point of the trim polylines (3D), as loop index and arc length.
TrimFoot nearest_trim(const std::vector<BdPolyline>& loops, const Vec3& p) {
  TrimFoot best;
  for (std::size_t k = 0; k < loops.size(); ++k) {
    const BdPolyline& L = loops[k];
    const int n = static_cast<int>(L.xyz.size());
    for (int i = 0; i < L.segment_count(); ++i) {
      const Vec3& a = L.xyz[i];
      const Vec3 ab = L.xyz[(i + 1) % n] - a;
      const double l2 = ab.squaredNorm();
      const double t = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
      const double d = (a + t * ab - p).norm();
      if (d < best.dist) best = {static_cast<int>(k), L.s_at(i, t), d};
    }
  }
  return best;
}

}  // namespace

PanelMesh mesh_curve_families(const SurfaceFace& face,
                              const std::vector<std::vector<SurfaceCurve>>& families,
                              const CurveFamilyMeshParams& params) {
  require_in_range("rod_length (mm)", params.rod_length, 1e-3, 1e9);
  require_in_range("min_edge_fraction", params.min_edge_fraction, 0.0, 0.9);
  require_in_range("corner_angle (deg)", params.corner_angle, 1.0, 179.0);
  require_in_range("trim_deflection (mm)", params.trim_deflection, 0.0, 1e9);
  require_in_range("max_panels", params.max_panels, 1, 1e9);
  const double size = face.model_size();
  const double deflection = trim_deflection(face, params.trim_deflection);
  const std::vector<TrimLoop> loops = face.trim_loops(deflection);
  const std::vector<BdPolyline> boundary = select_bd_sources(face, loops, {}).boundary;

  guide_detail::Context cx{face, {}, params.rod_length, params.rod_length, 1e-9 * size, 0, {}};
  cx.inside = UvTrimClassifier(loops, UvTrimClassifier::Options{-1, &face});

  // A curve piece whose end is within `on_trim` of a trim polyline ends on that
  // trim (the pieces are cut at the trim polylines; the trim nodes are snapped
  // onto the exact trim below); a piece lying along the trim (a guide on a boundary edge)
  // adds nothing the trim does not already give, and would overlap it.
  const double on_trim = std::max(10.0 * deflection, 1e-3 * params.rod_length);
  std::vector<BdCurve> curves;
  for (const auto& family : families)
    for (const SurfaceCurve& c : family)
      for (SurfaceCurve& run : guide_detail::inside_runs(cx, c, false)) {
        if (guide_detail::polyline_length(run.xyz) < 1e-6 * size) continue;
        const std::size_t n = run.xyz.size();
        const Vec3 mid = n % 2 ? run.xyz[n / 2] : 0.5 * (run.xyz[n / 2 - 1] + run.xyz[n / 2]);
        if (nearest_trim(boundary, mid).dist <= on_trim) continue;
        BdCurve b;
        b.uv = std::move(run.uv);
        b.xyz = std::move(run.xyz);
        for (const bool at_start : {true, false}) {
          const TrimFoot f = nearest_trim(boundary, at_start ? b.xyz.front() : b.xyz.back());
          if (f.dist > on_trim) continue;  // ends inside the face: pruned as dangling
          (at_start ? b.start : b.end) = BdCurveEnd{f.loop, f.s};
        }
        curves.push_back(std::move(b));
      }
  if (curves.empty()) throw InvalidParameter("guides: no curve crosses the face");

  BdNetworkParams np;
  np.corner_angle_deg = params.corner_angle;
  BdNetwork net = build_bd_network(face, boundary, curves, np);
  if (std::none_of(net.nodes.begin(), net.nodes.end(), [](const BdNode& n) { return n.loop < 0; }))
    throw InvalidParameter(
        "guides: the curves do not cross on the face (are the guides parallel?)");
  if (params.min_edge_fraction > 0)
    collapse_short_edges(face, net, params.min_edge_fraction * params.rod_length);

  // Trim nodes sit on the trim polylines; move them onto the trims' own curves.
  for (BdNode& n : net.nodes) {
    if (n.loop < 0) continue;
    n.uv = face.snap_to_trim(n.loop, n.uv);
    n.xyz = face.point(n.uv.x(), n.uv.y());
  }

  PanelMesh mesh;
  for (const BdNode& n : net.nodes) mesh.uv.push_back(n.uv), mesh.xyz.push_back(n.xyz);
  for (std::vector<int> p : net.panels) {
    p.erase(std::unique(p.begin(), p.end()), p.end());
    if (p.size() > 1 && p.front() == p.back()) p.pop_back();
    if (p.size() < 3) continue;
    if (!params.triangulate || p.size() == 3) {
      mesh.panels.push_back(std::move(p));
    } else if (p.size() == 4) {
      // The shorter diagonal: the flatter pair of triangles on a rhombus, and
      // the same choice on every cell of a regular grid.
      const double d02 = (mesh.xyz[p[0]] - mesh.xyz[p[2]]).norm();
      const double d13 = (mesh.xyz[p[1]] - mesh.xyz[p[3]]).norm();
      if (d02 <= d13) {
        mesh.panels.push_back({p[0], p[1], p[2]});
        mesh.panels.push_back({p[0], p[2], p[3]});
      } else {
        mesh.panels.push_back({p[1], p[2], p[3]});
        mesh.panels.push_back({p[1], p[3], p[0]});
      }
    } else {
      std::vector<Vec2> uv;
      for (int v : p) uv.push_back(mesh.uv[v]);
      for (const auto& t : triangulate_polygon(uv))
        mesh.panels.push_back({p[t[0]], p[t[1]], p[t[2]]});
    }
    if (static_cast<int>(mesh.panels.size()) > params.max_panels)
      throw LimitExceeded(std::to_string(mesh.panels.size()) +
                          " panels exceed max_panels = " + std::to_string(params.max_panels));
  }
  if (mesh.panels.empty())
    throw InvalidParameter("guides: the curves make no cells on the face (do they cross?)");
  remove_unused_vertices(mesh);
  if (face.reversed()) reverse_panels(mesh);
  build_rods(mesh);
  mesh.nominal_area = params.triangulate ? 0.5 * params.rod_length * params.rod_length
                                         : params.rod_length * params.rod_length;
  mesh.regular_corners = params.triangulate ? 3 : 4;
  return mesh;
}

}  // namespace tessella
