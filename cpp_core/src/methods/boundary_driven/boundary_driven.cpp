#include "tessella/boundary_driven.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>

#include "analysis/coverage.h"
#include "geometry/segment_closest.h"
#include "geometry/trim_deflection.h"
#include "mesh/seam_sides.h"
#include "methods/boundary_driven/bd_across_faces.h"
#include "methods/boundary_driven/bd_across_surfaces.h"
#include "methods/boundary_driven/bd_curves.h"
#include "methods/boundary_driven/bd_network.h"
#include "methods/boundary_driven/bd_onto_trim.h"
#include "methods/boundary_driven/bd_refine.h"
#include "methods/boundary_driven/bd_sources.h"
#include "methods/boundary_driven/bd_tensor.h"
#include "methods/boundary_driven/principal_field.h"
#include "tessella/errors.h"
#include "tessella/surface_face.h"

namespace tessella {

namespace {

// Refuses a mesh that does not tile the face: a trim loop no panel reaches (an
// opening swallowed by a panel), a panel folded over in (u,v), or panel areas
// not adding up to the face's area. The areas are compared in (u,v), where a
// tiling's panels add up to the trimmed region exactly: their 3D chord
// polygons are smaller than the curved surface by a share that grows with
// size / radius (a 1.4 km panel over OCCT's terrain covers 0.90 of it in 3D
// while the (u,v) tiling is complete). The tolerance is for the panels' chord
// edges along curved trims, which follow_trims replaces by the trim; the
// pipeline's coverage check (analysis/coverage.h) then measures gaps and
// overlaps exactly.
// The end of check_mesh's messages; boundary_driven_stages replaces it by
// the size that works, once it has found one.
const std::string kCoarseTail = ": use a smaller size)";

void check_mesh(const std::vector<BdPolyline>& boundary, const BdNetwork& net, double size) {
  const std::string hint = " (size " + std::to_string(size) +
                           " mm is too coarse for this face's openings and notches" + kCoarseTail;
  std::vector<char> reached(boundary.size(), 0);
  double area = 0;
  for (const auto& p : net.panels) {
    double uv_area = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const BdNode& n0 = net.nodes[p[i]];
      const BdNode& n1 = net.nodes[p[(i + 1) % p.size()]];
      uv_area += n0.uv.x() * n1.uv.y() - n1.uv.x() * n0.uv.y();
      if (n0.loop >= 0) reached[n0.loop] = 1;
    }
    if (!(uv_area > 0)) throw GeometryFailure("boundary-driven mesh: a panel folds over" + hint);
    area += 0.5 * uv_area;
  }
  double region = 0;  // loops keep the face on their left: holes count negative
  for (std::size_t k = 0; k < boundary.size(); ++k) {
    if (!reached[k])
      throw GeometryFailure("boundary-driven mesh: trim loop " + std::to_string(k) +
                            " is reached by no panel" + hint);
    const auto& uv = boundary[k].uv;
    for (std::size_t i = 0; i < uv.size(); ++i)
      region +=
          0.5 * (uv[i].x() * uv[(i + 1) % uv.size()].y() - uv[(i + 1) % uv.size()].x() * uv[i].y());
  }
  if (std::abs(area - region) > 0.04 * std::abs(region))
    throw GeometryFailure("boundary-driven mesh: the panels cover " +
                          std::to_string(area / region) + " of the face's (u,v) region" + hint);
}

// Whether a trim loop has a pole: a stretch that is one point in 3D but runs
// along (u,v) (a sphere's apex).
bool has_pole(const std::vector<BdPolyline>& boundary) {
  for (const BdPolyline& line : boundary)
    for (int i = 0; i < line.segment_count(); ++i)
      if (line.collapsed(i) && line.seg_end_uv(i) != line.uv[i]) return true;
  return false;
}

// Arc length along closed `line` of its point closest in (u,v) to `uv`.
double arc_at(const BdPolyline& line, const Vec2& uv) {
  const std::size_t n = line.uv.size();
  double best = std::numeric_limits<double>::infinity(), s = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = line.uv[i], d = line.uv[(i + 1) % n] - a;
    const double t = closest_fraction(a, d, uv);
    const double dist = (a + t * d - uv).squaredNorm();
    if (dist < best) best = dist, s = line.arc[i] + t * (line.arc[i + 1] - line.arc[i]);
  }
  return s;
}

// Boundary panels follow the trim: where a panel edge joins two nodes of the
// same trim loop and no other panel uses it, the trim polyline's points
// between them become outline points of that panel (not nodes: the rod still
// runs straight from node to node), as the grids' boundary panels do. Without
// them a boundary panel is its chord polygon, which leaves a sliver uncovered
// along a convex trim and covers part of an opening along a concave one
// (0.3-2.3% of the face on the bundled examples). Panels run counter-clockwise
// in (u,v) and loops keep the face on their left, so the edge a -> b runs
// forward along the loop.
void follow_trims(const std::vector<BdPolyline>& boundary, const std::vector<BdNode>& nodes,
                  PanelMesh& m) {
  std::map<std::pair<int, int>, int> uses;
  for (const auto& p : m.panels)
    for (std::size_t i = 0; i < p.size(); ++i)
      ++uses[{std::min(p[i], p[(i + 1) % p.size()]), std::max(p[i], p[(i + 1) % p.size()])}];
  m.is_node.assign(m.uv.size(), 1);
  for (auto& p : m.panels) {
    std::vector<int> out;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const int a = p[i], b = p[(i + 1) % p.size()];
      out.push_back(a);
      const int loop = nodes[a].loop;
      if (loop < 0 || nodes[b].loop != loop || uses[{std::min(a, b), std::max(a, b)}] != 1)
        continue;
      const BdPolyline& line = boundary[static_cast<std::size_t>(loop)];
      const double len = line.length();
      const double sa = arc_at(line, m.uv[a]);
      double ahead = arc_at(line, m.uv[b]) - sa;
      if (ahead < 0) ahead += len;
      if (!(ahead > 0) || ahead > 0.5 * len) continue;  // not a short run along the loop
      const std::size_t n = line.uv.size();
      // First polyline vertex after sa, then every vertex until sa + ahead.
      std::size_t k = static_cast<std::size_t>(
          std::upper_bound(line.arc.begin(), line.arc.end() - 1, sa) - line.arc.begin());
      std::vector<std::size_t> between;
      for (std::size_t step = 0; step < n; ++step, ++k) {
        const std::size_t idx = k % n;
        double along = line.arc[idx] + (k >= n ? len : 0.0) - sa;
        if (along <= 0) along += len;
        if (along >= ahead) break;
        between.push_back(idx);
      }
      // A straight run in (u,v) (an iso-line border) adds nothing to the outline.
      const Vec2 chord = m.uv[b] - m.uv[a];
      bool straight = true;
      for (std::size_t idx : between) {
        const Vec2 d = line.uv[idx] - m.uv[a];
        if (std::abs(chord.x() * d.y() - chord.y() * d.x()) > 1e-12 * chord.squaredNorm())
          straight = false;
      }
      if (straight) continue;
      // A point this near (3D) the outline's last point or b adds nothing
      // but a side no cutter can draw: a pole's stretch (one point in 3D;
      // one is enough), or a polyline point next to a node snapped onto the
      // trim's own curve (notched_shell: 0.2 um from a trim corner at every
      // size, 0.8 um from a curve's end). A vertex of the B-rep wire only
      // goes where it is that node (within `same`): in a face set it may be
      // the node of the face across, which the join needs in this outline
      // (OCCT's shell1 and a STEP part's micro edge: T-junctions, panels
      // overlapping in space).
      const double beside = 1e-6 * len, same = 1e-9 * len;
      for (std::size_t idx : between) {
        const Vec3& last = m.xyz[static_cast<std::size_t>(out.back())];
        const double gap = std::min((line.xyz[idx] - last).norm(), (line.xyz[idx] - m.xyz[b]).norm());
        if (gap <= (line.is_corner(idx) ? same : beside)) continue;
        out.push_back(static_cast<int>(m.uv.size()));
        m.uv.push_back(line.uv[idx]);
        m.xyz.push_back(line.xyz[idx]);
        m.is_node.push_back(0);
      }
    }
    p = std::move(out);
  }
}

}  // namespace

namespace {

void check_params(const SurfaceFace& face, const BoundaryDrivenParams& params) {
  const double ms = face.model_size();
  require_in_range("size (mm)", params.size, 1e-4 * ms, ms);
  require_in_range("rho", params.rho, 0.5, 8.0);
  require_in_range("skew_ratio", params.skew_ratio, 0.0, 1.0);
  require_in_range("smoothing_iterations", params.smoothing_iterations, 0, 1000);
  require_in_range("trim_deflection (mm)", params.trim_deflection, 0.0, 0.01 * ms);
  require_in_range("min_edge_fraction", params.min_edge_fraction, 0.0, 0.9);
  require_in_range("angle_target", params.angle_target_deg, 0.0, 90.0);
  require_in_range("angle_passes", params.angle_passes, 0, 1000);
  require_in_range("max_panels", params.max_panels, 1, 1e8);
  require_in_range("boundary_blend", params.boundary_blend, 0.0, 100.0);
  require_in_range("field_smoothness", params.field_smoothness, 1e-3, 100.0);
  const double estimate = face.area() / (params.size * params.size);
  if (estimate > params.max_panels)
    throw LimitExceeded("about " + std::to_string(static_cast<long long>(estimate)) +
                        " panels would exceed max_panels = " + std::to_string(params.max_panels) +
                        ": raise size or max_panels");
}

// Stages 1-3: sources, field, curves. Returns the spacing they were traced at.
double trace_stages(const SurfaceFace& face, const BoundaryDrivenParams& params,
                    BoundaryDrivenResult& r, int start_shift = 0) {
  const double ms = face.model_size();
  const double deflection = trim_deflection(face, params.trim_deflection);
  const BdSources src =
      select_bd_sources(face, face.trim_loops(deflection), params.sources, start_shift);
  r.boundary = src.boundary;
  const double spacing = params.quadrangulate ? 2.0 * params.size : params.size;

  BdTensorParams tp;
  tp.rho = params.rho;
  tp.sample_spacing = std::min(0.25 * spacing, ms);
  const BdTensor tensor = build_bd_tensor(face, src.sources, tp);

  BdCurveParams cp;
  cp.spacing = std::min(spacing, ms);
  cp.step_fraction = params.step_fraction;
  cp.corner_angle_deg = params.corner_angle_deg;
  BdTensorGrid principal;
  if (params.principal_directions) {
    int nu = 0, nv = 0;
    bd_field_grid_size(face, cp.spacing, nu, nv);
    PrincipalFieldParams fp;
    fp.blend_distance = params.boundary_blend * cp.spacing;
    fp.smoothness = params.field_smoothness;
    principal = principal_curvature_field(face, tensor, nu, nv, fp);
    cp.field = &principal;
  }
  r.curves = trace_bd_curves(face, tensor, r.boundary, cp);
  return cp.spacing;
}

// Trim nodes `pinned` says lie on an edge shared with another face become
// corners: never moved or removed, so both faces keep the curves' crossings.
// Only after the short edges are collapsed: a crossing next to a trim corner
// still goes into that corner (as a corner, it could take the corner away).
using PinnedTest = std::function<bool(const Vec2&)>;
void pin_shared_edge_nodes(BdNetwork& net, const PinnedTest& pinned, bool as_corners) {
  if (!pinned) return;
  for (BdNode& n : net.nodes) {
    if (n.loop < 0 || n.corner || !(n.shared || pinned(n.uv))) continue;
    n.shared = true;
    n.corner = as_corners;
  }
}

// Stages 4-6 from r.boundary and r.curves traced `spacing` apart: the network,
// its refinement and the panels.
void mesh_stages(const SurfaceFace& face, const BoundaryDrivenParams& params, double spacing,
                 const PinnedTest& pinned, BoundaryDrivenResult& r) {
  const double ms = face.model_size();
  BdNetworkParams np;
  np.corner_angle_deg = params.corner_angle_deg;
  r.network = build_bd_network(face, r.boundary, r.curves, np);
  if (r.network.panels.empty())
    throw GeometryFailure("the boundary-driven curve network has no faces");

  BdNetwork net = r.network;
  // A face of a union or a smooth group traced at the group's spacing may be
  // smaller than the edges it would collapse (a 0.05 mm face of OCCT's
  // Pump_Nut at 1.5 mm: a parameter error refused the whole set); a
  // geometric failure lets it trace on its own.
  if (!(params.min_edge_fraction * spacing <= ms))
    throw GeometryFailure("boundary-driven mesh: the face is smaller than its curves' spacing");
  r.collapsed_edges = collapse_short_edges(face, net, params.min_edge_fraction * spacing);
  r.removed_triangles = remove_skewed_triangles(net, params.skew_ratio);
  pin_shared_edge_nodes(net, pinned, false);
  if (params.quadrangulate) quadrangulate(face, r.boundary, net, pinned ? 0.75 * spacing : 0.0);
  pin_shared_edge_nodes(net, pinned, true);
  smooth_bd_mesh(face, r.boundary, net, params.smoothing_iterations);
  if (params.angle_target_deg > 0)
    r.angle_moves =
        improve_bd_angles(face, r.boundary, net, params.angle_target_deg, params.angle_passes);

  // Trim nodes sit on the trim polylines (chords within the deflection); move
  // them onto the trims' own curves on the surface.
  for (BdNode& n : net.nodes) {
    if (n.loop < 0) continue;
    n.uv = face.snap_to_trim(n.loop, n.uv);
    n.xyz = face.point(n.uv.x(), n.uv.y());
  }
  untangle_trim_crossings(face, r.boundary, net);
  // (a quarter of a panel: farther off, the node is no sliver's corner)
  move_crossing_nodes_onto_trims(face, r.boundary, net, 0.25 * params.size);
  check_mesh(r.boundary, net, params.size);

  PanelMesh& m = r.mesh;
  for (const BdNode& n : net.nodes) m.uv.push_back(n.uv), m.xyz.push_back(n.xyz);
  m.panels = net.panels;
  follow_trims(r.boundary, net.nodes, m);
  // The nodes a pole's stretch holds (one per (u,v) position along it, so the
  // network stayed planar in (u,v)) are one point in 3D: one vertex.
  if (has_pole(r.boundary)) weld_coincident_vertices(m, 1e-9 * ms);
  // A face closed round its period (a full cylinder) has its seam traced
  // from both sides: joined as two faces along a shared edge.
  join_seam_sides(face, m);
  // Too few curves round a closed direction somewhere (a cone's smaller rim
  // at a size near its girth): one cell went round the whole top as a ring
  // panel, which the boundary pieces then split across the seam.
  if (widest_panel_round(face, m) >= 0.5 - 1e-9)
    throw GeometryFailure(
        "boundary-driven mesh: a panel goes half way round the closed face (size " +
        std::to_string(params.size) + " mm is too coarse for its girth" + kCoarseTail);
  if (static_cast<long long>(m.panels.size()) > params.max_panels)
    throw LimitExceeded(std::to_string(m.panels.size()) +
                        " panels exceed max_panels = " + std::to_string(params.max_panels));
  remove_unused_vertices(m);
  if (face.reversed()) reverse_panels(m);
  build_rods(m);
  m.nominal_area = params.size * params.size;
  // The method checks its own tiling both ways before it returns (the
  // pipeline checks again after its later stages), so that a size that
  // leaves a gap or an overlap is refused here and the search for a size
  // that works (boundary_driven_stages) sees it.
  const std::string problem =
      coverage_message(measure_coverage(face, m, {}), "boundary-driven mesh");
  if (!problem.empty())
    throw GeometryFailure(problem + " (size " + std::to_string(params.size) +
                          " mm is too coarse for this face's openings and notches" + kCoarseTail);
}

BoundaryDrivenResult build_boundary_driven(const SurfaceFace& face,
                                           const BoundaryDrivenParams& params,
                                           int start_shift = 0) {
  check_params(face, params);
  BoundaryDrivenResult r;
  const double spacing = trace_stages(face, params, r, start_shift);
  mesh_stages(face, params, spacing, nullptr, r);
  return r;
}

// The size at which `round` curves go round a rim: curves are a size apart,
// two sizes when quadrangulated (each cell then splits in two).
double size_for_curves_round(const BoundaryDrivenParams& params, double rim, double round) {
  return rim / (round * (params.quadrangulate ? 2.0 : 1.0));
}

// Round a closed direction at least three curves, two where every cell is
// split in two round it, so that three or four panels go round, as the grids
// take three cells at least: with fewer, a 300 mm column at 500 mm was two
// flat panels through its axis in each row, the same in space (unbuildable,
// and unseen by the coverage in (u,v)), and at 800 mm 100% unmeshed. Counted
// as bd_curves places seeds along the longest rim (the nearest whole number
// of spacings); the size, not only the spacing, is reduced, so that the
// later stages (slivers against size^2) see the panels' real size.
BoundaryDrivenParams with_curves_round(const BoundaryDrivenParams& params,
                                       const std::vector<double>& rims) {
  BoundaryDrivenParams p = params;
  const double round = params.quadrangulate ? 2.0 : 3.0;
  const double spacing = params.quadrangulate ? 2.0 * params.size : params.size;
  if (!rims.empty() && std::lround(rims.front() / spacing) < round)
    p.size = size_for_curves_round(params, rims.front(), round);
  return p;
}

}  // namespace

BoundaryDrivenResult boundary_driven_stages(const SurfaceFace& face,
                                            const BoundaryDrivenParams& asked) {
  const std::vector<double> rims =
      rim_lengths(face, face.trim_loops(trim_deflection(face, asked.trim_deflection)));
  const BoundaryDrivenParams params = with_curves_round(asked, rims);
  try {
    return build_boundary_driven(face, params);
  } catch (const GeometryFailure& e) {
    std::string message = e.what();
    const std::size_t tail = message.rfind(kCoarseTail);
    if (tail == std::string::npos || tail + kCoarseTail.size() != message.size()) throw;
    // "Use a smaller size" is no help on a face without openings: find the
    // size that works (a quarter smaller each try, down to a quarter, within
    // max_panels) and say it. Only a failing call pays for the search.
    message.erase(tail);
    // Where the seeds start along the loops decides the layout (which of two
    // close curves is kept): two other starts at the same size first.
    for (int shift : {1, 2}) {
      try {
        return build_boundary_driven(face, params, shift);
      } catch (const GeometryFailure&) {
      }
    }
    // On a closed face, curves as far apart as a smaller rim allows (a
    // cone's: three round its larger rim are too few for the smaller one),
    // the coarsest first.
    for (double rim : rims)
      for (double round : {2.0, 3.0}) {
        BoundaryDrivenParams smaller = params;
        smaller.size = size_for_curves_round(params, rim, round);
        if ((round == 2.0 && !params.quadrangulate) || !(smaller.size < params.size)) continue;
        try {
          return build_boundary_driven(face, smaller);
        } catch (const GeometryFailure&) {
        }
      }
    // A quarter smaller each try, down to a quarter of the size; a face set's
    // face (take_a_smaller_size) down to a sixteenth: a 300 mm disk capping
    // a column takes 64 mm at most, and refusing it refused the whole set.
    const double factors[] = {0.75, 0.56, 0.42, 0.32, 0.25, 0.19, 0.14, 0.105, 0.079, 0.0625};
    const int tries = params.take_a_smaller_size ? 10 : 5;
    for (int t = 0; t < tries; ++t) {
      BoundaryDrivenParams smaller = params;
      smaller.size = params.size * factors[t];
      if (face.area() / (smaller.size * smaller.size) > params.max_panels ||
          smaller.size < 1e-4 * face.model_size())
        break;
      std::optional<BoundaryDrivenResult> works;
      try {
        works = build_boundary_driven(face, smaller);
      } catch (const GeometryFailure&) {
      }
      if (works) {
        if (params.take_a_smaller_size) return std::move(*works);
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.6g", smaller.size);
        throw GeometryFailure(message + ": size " + buf + " mm works)");
      }
    }
    throw GeometryFailure(message + (params.take_a_smaller_size
                                         ? ": no size down to a sixteenth of it works either)"
                                         : ": no size down to a quarter of it works either)"));
  }
}

PanelMesh boundary_driven(const SurfaceFace& face, const BoundaryDrivenParams& params) {
  return boundary_driven_stages(face, params).mesh;
}

PanelMesh curvature_lines(const SurfaceFace& face, const BoundaryDrivenParams& params) {
  BoundaryDrivenParams p = params;
  p.principal_directions = true;
  return boundary_driven_stages(face, p).mesh;
}

}  // namespace tessella

namespace tessella {

BdSurfaceCurves trace_bd_surface_curves(const SurfaceFace& union_face,
                                        const BoundaryDrivenParams& params) {
  check_params(union_face, params);
  BoundaryDrivenResult r;
  BdSurfaceCurves out;
  out.spacing = trace_stages(union_face, params, r);
  out.curves = std::move(r.curves);
  out.boundary = std::move(r.boundary);
  // The faces' trim polylines and the union's discretize the same edges
  // apart (each within its deflection): points within a few deflections, in
  // (u,v), lie on the same trim.
  const UvBounds b = union_face.bounds();
  const double uv_diagonal = std::hypot(b.u_max - b.u_min, b.v_max - b.v_min);
  const double deflection = trim_deflection(union_face, params.trim_deflection);
  out.on_trim = uv_diagonal * (4.0 * deflection / union_face.model_size() + 1e-9);
  return out;
}

PanelMesh boundary_driven_on_curves(const SurfaceFace& member, const BoundaryDrivenParams& params,
                                    const BdSurfaceCurves& traced) {
  check_params(member, params);
  BoundaryDrivenResult r;
  const double deflection = trim_deflection(member, params.trim_deflection);
  r.boundary = select_bd_sources(member, member.trim_loops(deflection), {}).boundary;
  r.curves = clip_bd_curves(member, traced.curves, r.boundary, traced.on_trim);
  // A trim node farther than on_trim from the union's trim is on a shared edge.
  const PinnedTest on_shared_edge = [&traced](const Vec2& uv) {
    for (const BdPolyline& line : traced.boundary)
      for (int i = 0; i < line.segment_count(); ++i) {
        const Vec2 a = line.uv[i], d = line.seg_end_uv(i) - a;
        const double t = closest_fraction(a, d, uv);
        if ((a + t * d - uv).norm() <= traced.on_trim) return false;
      }
    return true;
  };
  mesh_stages(member, params, traced.spacing, on_shared_edge, r);
  return std::move(r.mesh);
}

PanelMesh boundary_driven_on_group_curves(const SurfaceFace& face,
                                          const BoundaryDrivenParams& params,
                                          const BdGroupMember& member, std::vector<BdCurve> curves,
                                          double spacing) {
  check_params(face, params);
  BoundaryDrivenResult r;
  r.boundary = member.boundary;
  r.curves = std::move(curves);
  // Nodes on the smooth edges stay where the curves cross them (the face
  // across has a node at the same point).
  const PinnedTest on_smooth_edge = [&face, &member](const Vec2& uv) {
    return first_track_near(member.smooth, face.point(uv.x(), uv.y()), member.tolerance) >= 0;
  };
  mesh_stages(face, params, spacing, on_smooth_edge, r);
  return std::move(r.mesh);
}

}  // namespace tessella
