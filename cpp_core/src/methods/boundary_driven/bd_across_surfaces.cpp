#include "methods/boundary_driven/bd_across_surfaces.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/segment_closest.h"
#include "geometry/trim_deflection.h"
#include "methods/boundary_driven/bd_sources.h"
#include "tessella/errors.h"
#include "tessella/surface_face.h"

namespace tessella {

double bd_edge_tolerance(const SurfaceFace& face, const BoundaryDrivenParams& params) {
  return 4.0 * trim_deflection(face, params.trim_deflection) + 1e-6 * face.model_size();
}

BdGroupMember bd_group_member(const SurfaceFace& face, const BoundaryDrivenParams& params) {
  BdGroupMember m;
  m.face = &face;
  const double deflection = trim_deflection(face, params.trim_deflection);
  m.boundary = select_bd_sources(face, face.trim_loops(deflection), {}).boundary;
  m.tolerance = bd_edge_tolerance(face, params);
  return m;
}

std::vector<BdPolyline> bd_free_boundary_runs(const std::vector<BdPolyline>& boundary,
                                              const std::vector<EdgeTrack>& skip,
                                              double tolerance) {
  auto skipped = [&](const Vec3& p) { return first_track_near(skip, p, tolerance) >= 0; };
  std::vector<BdPolyline> runs;
  for (const BdPolyline& line : boundary) {
    const std::size_t n = line.xyz.size();
    std::vector<char> off(n);
    std::size_t off_count = 0;
    for (std::size_t i = 0; i < n; ++i) off_count += (off[i] = skipped(line.xyz[i]) ? 0 : 1);
    if (off_count == n) {
      runs.push_back(line);
      continue;
    }
    if (off_count == 0) continue;
    // Start after a skipped point, so that no run wraps past the start. A
    // run keeps the skipped points at its ends (where the edge meets it).
    std::size_t first = 0;
    while (off[first]) ++first;
    BdPolyline run;
    run.outer = line.outer;
    auto add = [&](std::size_t i) {
      run.uv.push_back(line.uv[i]);
      run.xyz.push_back(line.xyz[i]);
    };
    for (std::size_t step = 1; step <= n; ++step) {
      const std::size_t i = (first + step) % n, prev = (first + step - 1) % n;
      if (!off[i]) {
        if (!run.uv.empty()) {
          add(i);
          finish_polyline(run);
          runs.push_back(run);
          run = BdPolyline();
          run.outer = line.outer;
        }
        continue;
      }
      if (run.uv.empty()) add(prev);
      add(i);
    }
  }
  return runs;
}

namespace {

Vec3 xyz_at(const BdPolyline& line, double s) {
  const int i = line.segment_at(s);
  const std::size_t n = line.xyz.size();
  const double l =
      line.arc[static_cast<std::size_t>(i) + 1] - line.arc[static_cast<std::size_t>(i)];
  const double t = l > 0 ? (s - line.arc[static_cast<std::size_t>(i)]) / l : 0.0;
  return line.xyz[static_cast<std::size_t>(i)] +
         t * (line.xyz[(static_cast<std::size_t>(i) + 1) % n] -
              line.xyz[static_cast<std::size_t>(i)]);
}

}  // namespace

std::vector<Vec3> bd_chain_seeds(const std::vector<BdPolyline>& runs, double spacing,
                                 double corner_angle_deg, double tolerance) {
  std::vector<BdPolyline> chains;
  std::vector<char> used(runs.size(), 0);
  for (std::size_t r = 0; r < runs.size(); ++r) {
    if (used[r] || runs[r].xyz.size() < 2) continue;
    used[r] = 1;
    BdPolyline chain;
    chain.xyz = runs[r].xyz;
    chain.closed = runs[r].closed;
    chain.outer = runs[r].outer;
    // Open runs joined at their ends, forward then backward, in run order.
    for (bool grew = !chain.closed; grew;) {
      grew = false;
      for (std::size_t o = 0; o < runs.size() && !grew; ++o) {
        if (used[o] || runs[o].closed || runs[o].xyz.size() < 2) continue;
        const std::vector<Vec3>& x = runs[o].xyz;
        std::vector<Vec3> piece;
        bool at_back = true;
        if ((x.front() - chain.xyz.back()).norm() <= tolerance) {
          piece.assign(x.begin() + 1, x.end());
        } else if ((x.back() - chain.xyz.back()).norm() <= tolerance) {
          piece.assign(x.rbegin() + 1, x.rend());
        } else if ((x.back() - chain.xyz.front()).norm() <= tolerance) {
          piece.assign(x.begin(), x.end() - 1);
          at_back = false;
        } else if ((x.front() - chain.xyz.front()).norm() <= tolerance) {
          piece.assign(x.rbegin(), x.rend() - 1);
          at_back = false;
        } else {
          continue;
        }
        if (at_back)
          chain.xyz.insert(chain.xyz.end(), piece.begin(), piece.end());
        else
          chain.xyz.insert(chain.xyz.begin(), piece.begin(), piece.end());
        used[o] = 1;
        chain.outer = chain.outer || runs[o].outer;
        grew = true;
      }
    }
    if (!chain.closed && chain.xyz.size() > 2 &&
        (chain.xyz.front() - chain.xyz.back()).norm() <= tolerance) {
      chain.xyz.pop_back();
      chain.closed = true;
    }
    // A closed chain starts at its least point (x, then y, then z), so that
    // the seeds do not depend on the order the faces and wires are listed.
    if (chain.closed) {
      const auto least =
          std::min_element(chain.xyz.begin(), chain.xyz.end(), [](const Vec3& a, const Vec3& b) {
            return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
          });
      std::rotate(chain.xyz.begin(), least, chain.xyz.end());
    }
    chain.uv.assign(chain.xyz.size(), Vec2::Zero());
    finish_polyline(chain);
    chains.push_back(std::move(chain));
  }
  // The outer boundary first (one face's outer loop comes first).
  std::stable_sort(chains.begin(), chains.end(),
                   [](const BdPolyline& a, const BdPolyline& b) { return a.outer && !b.outer; });
  std::vector<Vec3> out;
  for (const BdPolyline& chain : chains) {
    const double len = chain.length();
    if (!(len > 0)) continue;
    // One face's rule (bd_curves.cpp, Tracer::run).
    const std::vector<double> corners = bd_corners(chain, corner_angle_deg);
    std::vector<double> at;
    if (corners.empty()) {
      const int m = std::max(4, static_cast<int>(std::lround(len / spacing)));
      for (int j = 0; j < m; ++j) at.push_back(len * j / m);
    } else {
      const std::size_t spans = chain.closed ? corners.size() : corners.size() - 1;
      for (std::size_t c = 0; c < spans; ++c) {
        const double a = corners[c];
        const double b = c + 1 < corners.size() ? corners[c + 1] : corners[0] + len;
        const int m = static_cast<int>(std::lround((b - a) / spacing));
        for (int j = 1; j < m; ++j) at.push_back(a + (b - a) * j / m);
      }
    }
    for (double s : at) out.push_back(xyz_at(chain, s));
  }
  return out;
}

namespace {

// Where a point of the group's free boundary lies on a member's trims: the
// nearest point of its segments off the smooth edges, within the tolerance.
struct OnMember {
  int member = -1;
  BdCurveEnd at;
};
OnMember locate_on_members(const std::vector<BdGroupMember>& members,
                           const std::vector<std::vector<std::vector<int>>>& across,
                           const Vec3& x) {
  OnMember best;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t m = 0; m < members.size(); ++m) {
    const BdGroupMember& g = members[m];
    for (std::size_t k = 0; k < g.boundary.size(); ++k) {
      const BdPolyline& line = g.boundary[k];
      for (int i = 0; i < line.segment_count(); ++i) {
        if (across[m][k][static_cast<std::size_t>(i)] >= 0) continue;
        const Vec3 a = line.xyz[i], d = line.xyz[(i + 1) % line.xyz.size()] - a;
        const double t = closest_fraction(a, d, x);
        const double dist = (a + t * d - x).norm();
        if (dist <= g.tolerance && dist < best_d) {
          best_d = dist;
          best.member = static_cast<int>(m);
          best.at = {static_cast<int>(k), line.s_at(i, t)};
        }
      }
    }
  }
  return best;
}

}  // namespace

BdGroupCurves trace_bd_group_curves(const std::vector<BdGroupMember>& members,
                                    const BoundaryDrivenParams& params) {
  BdGroupCurves out;
  if (members.empty()) return out;
  double smallest = std::numeric_limits<double>::infinity(), tol = 0;
  for (const BdGroupMember& m : members) {
    smallest = std::min(smallest, m.face->model_size());
    tol = std::max(tol, m.tolerance);
  }
  const double spacing = std::min(params.quadrangulate ? 2.0 * params.size : params.size, smallest);
  // Per member, loop and segment: the member across a smooth edge (both ends
  // of the segment on it), -1 elsewhere.
  std::vector<std::vector<std::vector<int>>> across(members.size());
  BdTensor tensor;
  tensor.rho = params.rho;
  std::vector<BdPolyline> all_runs;
  for (std::size_t m = 0; m < members.size(); ++m) {
    const BdGroupMember& g = members[m];
    for (const BdPolyline& line : g.boundary) {
      const std::size_t n = line.xyz.size();
      std::vector<int> edge(n);
      for (std::size_t i = 0; i < n; ++i)
        edge[i] = first_track_near(g.smooth, line.xyz[i], g.tolerance);
      std::vector<int> to(static_cast<std::size_t>(std::max(line.segment_count(), 0)), -1);
      for (std::size_t i = 0; i < to.size(); ++i) {
        const int a = edge[i], b = edge[(i + 1) % n];
        if (a >= 0 && (a == b || b >= 0)) to[i] = g.smooth_to[static_cast<std::size_t>(a)];
      }
      across[m].push_back(std::move(to));
    }
    // The sources: the members' trims off the smooth edges, in 3D (a sample
    // of one face weighs on the others by its distance, as on one face).
    const std::vector<BdPolyline> runs = bd_free_boundary_runs(g.boundary, g.smooth, g.tolerance);
    if (!runs.empty()) {
      BdTensorParams tp;
      tp.rho = params.rho;
      tp.sample_spacing = 0.25 * spacing;
      try {
        const BdTensor t = build_bd_tensor(*g.face, runs, tp);
        tensor.samples.insert(tensor.samples.end(), t.samples.begin(), t.samples.end());
      } catch (const InvalidGeometry&) {  // no usable length on this face
      }
    }
    all_runs.insert(all_runs.end(), runs.begin(), runs.end());
  }
  if (tensor.samples.empty())
    throw GeometryFailure("the faces joined smoothly have no free boundary to start from");
  std::vector<BdChart> charts(members.size());
  for (std::size_t m = 0; m < members.size(); ++m) {
    charts[m].face = members[m].face;
    charts[m].boundary = &members[m].boundary;
    charts[m].across = across[m];
    for (const BdPolyline& line : members[m].boundary)
      charts[m].plan.dictated.emplace_back(
          static_cast<std::size_t>(std::max(line.segment_count(), 0)), 1);
  }
  // The seeds in order along the group's boundary, each on the member it lies on.
  int order = 0;
  for (const Vec3& x : bd_chain_seeds(all_runs, spacing, params.corner_angle_deg, tol)) {
    const OnMember on = locate_on_members(members, across, x);
    if (on.member < 0) continue;
    BdSeedPlan& plan = charts[static_cast<std::size_t>(on.member)].plan;
    plan.seeds.push_back(on.at);
    plan.order.push_back(order++);
  }
  BdCurveParams cp;
  cp.spacing = spacing;
  cp.step_fraction = params.step_fraction;
  cp.corner_angle_deg = params.corner_angle_deg;
  out.curves = trace_bd_curves_across(charts, tensor, cp);
  out.spacing = spacing;
  return out;
}

}  // namespace tessella
