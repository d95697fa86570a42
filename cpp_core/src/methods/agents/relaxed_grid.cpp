#include "tessella/relaxed_grid.h"

#include <algorithm>
#include <cmath>

#include "mesh/cell_clipping.h"
#include "methods/agents/agent_walk.h"
#include "tessella/errors.h"
#include "tessella/surface_face.h"

namespace tessella {

PanelMesh relaxed_grid(const SurfaceFace& face, const RelaxedGridParams& params,
                       RelaxedGridReport* report) {
  require_in_range("u_count", params.u_count, 1, 1e6);
  require_in_range("v_count", params.v_count, 1, 1e6);
  require_in_range("max_iterations", params.max_iterations, 0, 1e6);
  require_in_range("tolerance", params.tolerance, 0.0, 1.0);
  require_in_range("weight", params.weight, 1e-6, 1.0);
  require_in_range("max_panels", params.clip.max_panels, 1, 1e8);
  const double cells = double(params.u_count) * double(params.v_count);
  if (cells > params.clip.max_panels) {
    throw LimitExceeded(
        "the grid would have " + std::to_string(static_cast<long long>(cells)) +
        " panels, more than max_panels = " + std::to_string(params.clip.max_panels) +
        ": choose smaller counts or raise max_panels");
  }
  const UvBounds b = face.bounds();
  const int nu = params.u_count + 1, nv = params.v_count + 1;
  const double su = b.u_max - b.u_min, sv = b.v_max - b.v_min;
  std::vector<Vec2> uv(std::size_t(nu) * nv);
  auto at = [nu](int i, int j) { return std::size_t(j) * nu + i; };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i)
      uv[at(i, j)] = {b.u_min + su * i / (nu - 1), b.v_min + sv * j / (nv - 1)};

  RelaxedGridReport rep;
  std::vector<Vec3> P(uv.size());
  for (int it = 0; it < params.max_iterations; ++it) {
    for (std::size_t k = 0; k < uv.size(); ++k) P[k] = face.point(uv[k].x(), uv[k].y());
    double largest = 0;
    for (int j = 0; j < nv; ++j) {
      for (int i = 0; i < nu; ++i) {
        const std::size_t k = at(i, j);
        const bool u_border = i == 0 || i == nu - 1, v_border = j == 0 || j == nv - 1;
        if (u_border && v_border) continue;  // corners stay
        Vec3 f = Vec3::Zero();
        double total = 0, length = 0;
        int rods = 0;
        const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
        for (int n = 0; n < 4; ++n) {
          const int ii = i + di[n], jj = j + dj[n];
          if (ii < 0 || ii >= nu || jj < 0 || jj >= nv) continue;
          const std::size_t m = at(ii, jj);
          const double e = agents::path_deviation(face, uv[k], uv[m], P[k], P[m]);
          const Vec3 rod = P[m] - P[k];
          const double l = rod.norm();
          if (l <= 0) continue;
          f += e * rod / l;
          total += e;
          length += l;
          ++rods;
        }
        if (rods == 0 || total <= 0) continue;
        const SurfacePoint d = face.derivatives(uv[k].x(), uv[k].y());
        Vec3 n = d.du.cross(d.dv);
        if (n.norm() <= 0) continue;
        n.normalize();
        const Vec3 q = f - f.dot(n) * n;  // tangential part only
        const Vec3 dx = params.weight * (length / rods) * q / total;
        // (u,v) step: least squares of [du dv] duv = dx.
        const double a = d.du.dot(d.du), c = d.du.dot(d.dv), e = d.dv.dot(d.dv);
        const double det = a * e - c * c;
        if (!(det > 0)) continue;
        const double ru = d.du.dot(dx), rv = d.dv.dot(dx);
        double du = (e * ru - c * rv) / det, dv = (a * rv - c * ru) / det;
        if (u_border) du = 0;  // slide along the border
        if (v_border) dv = 0;
        // Never past a neighbour: at most 0.3 of the gap on that side.
        if (!u_border) {
          const double gap =
              du > 0 ? uv[at(i + 1, j)].x() - uv[k].x() : uv[k].x() - uv[at(i - 1, j)].x();
          du = std::clamp(du, -0.3 * std::max(gap, 0.0), 0.3 * std::max(gap, 0.0));
        }
        if (!v_border) {
          const double gap =
              dv > 0 ? uv[at(i, j + 1)].y() - uv[k].y() : uv[k].y() - uv[at(i, j - 1)].y();
          dv = std::clamp(dv, -0.3 * std::max(gap, 0.0), 0.3 * std::max(gap, 0.0));
        }
        // Gauss-Seidel: the move is seen by the next nodes at once (a Jacobi
        // update lets neighbours overshoot together into a zig-zag).
        uv[k] = {std::clamp(uv[k].x() + du, b.u_min, b.u_max),
                 std::clamp(uv[k].y() + dv, b.v_min, b.v_max)};
        P[k] = face.point(uv[k].x(), uv[k].y());
        largest = std::max({largest, std::abs(du) / su, std::abs(dv) / sv});
      }
    }
    rep.iterations = it + 1;
    rep.last_move = largest;
    if (largest <= params.tolerance) {
      rep.converged = true;
      break;
    }
  }
  if (params.max_iterations == 0) rep.converged = true;

  // The relaxed cells cover the bounds rectangle exactly (border nodes slide
  // along it): cut by the trims, they tile the face.
  PanelMesh mesh = clip_cells(face, uv, nu, nv, params.clip);
  if (report) *report = rep;
  return mesh;
}

}  // namespace tessella
