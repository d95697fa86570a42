#include "tessella/flatten.h"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include "mesh/panel_model.h"
#include "tessella/errors.h"
#include "tessella/face_set.h"
#include "tessella/panel_mesh.h"
#include "tessella/surface_face.h"

namespace tessella {

namespace {

double signed_area2(const std::vector<Vec2>& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2& q = p[i];
    const Vec2& r = p[(i + 1) % p.size()];
    a += q.x() * r.y() - r.x() * q.y();
  }
  return a;
}

}  // namespace

FlatPatch flatten_patch(const SurfaceFace& face, const std::vector<Vec2>& corner_uv,
                        const FlattenParams& params) {
  require_in_range("subdivisions", params.subdivisions, 1, 64);
  const int n = static_cast<int>(corner_uv.size());
  if (n < 3) throw InvalidGeometry("a panel needs at least three corners");
  const int m = params.subdivisions;
  if (static_cast<double>(n - 2) * m * m > 4e6)
    throw LimitExceeded("flatten: " + std::to_string(n) + " corners x subdivisions " +
                        std::to_string(m) + "^2 exceed 4 million triangles; lower subdivisions");
  // Work counter-clockwise in (u,v); remember to reverse at the end.
  const bool ccw = signed_area2(corner_uv) >= 0;
  std::vector<Vec2> uv = corner_uv;
  if (!ccw) std::reverse(uv.begin(), uv.end());

  // Fine mesh: every triangle of the outline split on a barycentric grid.
  // Vertices are shared by their (u,v) rounded to a grid 1e-9 of the extent.
  double extent = 0;
  for (const Vec2& p : uv) extent = std::max(extent, (p - uv[0]).cwiseAbs().maxCoeff());
  const double key_scale = 1e9 / std::max(extent, 1e-300);
  std::map<std::pair<long long, long long>, int> index;
  std::vector<Vec2> vuv;
  auto vertex = [&](const Vec2& p) {
    const std::pair<long long, long long> key{std::llround((p.x() - uv[0].x()) * key_scale),
                                              std::llround((p.y() - uv[0].y()) * key_scale)};
    auto it = index.find(key);
    if (it != index.end()) return it->second;
    const int id = static_cast<int>(vuv.size());
    index.emplace(key, id);
    vuv.push_back(p);
    return id;
  };
  // Boundary first, so the outline walks the panel's edges.
  FlatPatch out;
  std::vector<int> boundary;
  for (int i = 0; i < n; ++i) {
    const Vec2 &a = uv[i], &b = uv[(i + 1) % n];
    for (int k = 0; k < m; ++k) boundary.push_back(vertex(a + (b - a) * (double(k) / m)));
  }
  std::vector<std::array<int, 3>> tris;
  for (const auto& t : triangulate_polygon(uv)) {
    const Vec2 &A = uv[t[0]], &B = uv[t[1]], &C = uv[t[2]];
    auto at = [&](int i, int j) {  // grid point i steps toward B, j toward C
      return vertex(A + (B - A) * (double(i) / m) + (C - A) * (double(j) / m));
    };
    for (int i = 0; i < m; ++i)
      for (int j = 0; i + j < m; ++j) {
        tris.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        if (i + j + 1 < m) tris.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  }
  const int nv = static_cast<int>(vuv.size());
  std::vector<Vec3> xyz(nv);
  for (int i = 0; i < nv; ++i) xyz[i] = face.point(vuv[i].x(), vuv[i].y());

  // LSCM: per triangle, in a local orthonormal frame, sum_j W_j U_j = 0 with
  // W_j = (x_{j+2} - x_{j+1}) + i (y_{j+2} - y_{j+1}), scaled by 1/sqrt(area).
  // Pin the two boundary vertices farthest apart in 3D (approximately).
  int p0 = boundary[0], p1 = boundary[0];
  double best = -1;
  for (int b : boundary)
    if ((xyz[b] - xyz[p0]).norm() > best) best = (xyz[b] - xyz[p0]).norm(), p1 = b;
  if (best <= 0) throw InvalidGeometry("flatten: the panel has no extent");
  std::vector<int> col(nv, -1);
  int nfree = 0;
  for (int i = 0; i < nv; ++i)
    if (i != p0 && i != p1) col[i] = nfree++;
  const Vec2 pin0(0, 0), pin1(best, 0);
  std::vector<Eigen::Triplet<double>> trip;
  std::vector<double> rhs;
  int row = 0;
  for (const auto& t : tris) {
    const Vec3 e1 = xyz[t[1]] - xyz[t[0]], e2 = xyz[t[2]] - xyz[t[0]];
    const Vec3 nrm = e1.cross(e2);
    const double area = 0.5 * nrm.norm();
    out.area_3d += area;
    if (area <= 0) continue;
    const Vec3 ex = e1.normalized(), ey = nrm.normalized().cross(ex);
    const Vec2 q[3] = {{0, 0}, {e1.norm(), 0}, {e2.dot(ex), e2.dot(ey)}};
    const double s = 1.0 / std::sqrt(area);
    double b_re = 0, b_im = 0;
    for (int j = 0; j < 3; ++j) {
      const double wr = s * (q[(j + 2) % 3].x() - q[(j + 1) % 3].x());
      const double wi = s * (q[(j + 2) % 3].y() - q[(j + 1) % 3].y());
      const int v = t[j];
      // real: wr u - wi v ; imag: wi u + wr v
      if (col[v] >= 0) {
        trip.emplace_back(row, 2 * col[v], wr);
        trip.emplace_back(row, 2 * col[v] + 1, -wi);
        trip.emplace_back(row + 1, 2 * col[v], wi);
        trip.emplace_back(row + 1, 2 * col[v] + 1, wr);
      } else {
        const Vec2& pin = v == p0 ? pin0 : pin1;
        b_re -= wr * pin.x() - wi * pin.y();
        b_im -= wi * pin.x() + wr * pin.y();
      }
    }
    rhs.push_back(b_re);
    rhs.push_back(b_im);
    row += 2;
  }
  Eigen::SparseMatrix<double> a(row, 2 * nfree);
  a.setFromTriplets(trip.begin(), trip.end());
  const Eigen::VectorXd b = Eigen::Map<Eigen::VectorXd>(rhs.data(), row);
  const Eigen::SparseMatrix<double> ata = a.transpose() * a;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(ata);
  if (solver.info() != Eigen::Success)
    throw GeometryFailure("flatten: the LSCM system is singular");
  const Eigen::VectorXd x = solver.solve(a.transpose() * b);
  std::vector<Vec2> flat(nv);
  for (int i = 0; i < nv; ++i)
    flat[i] = col[i] >= 0 ? Vec2(x[2 * col[i]], x[2 * col[i] + 1]) : (i == p0 ? pin0 : pin1);
  // Orientation: as seen from the front (counter-clockwise along the outline
  // when uv was counter-clockwise); scale to the 3D area.
  std::vector<Vec2> ring;
  for (int v : boundary) ring.push_back(flat[v]);
  double area_flat = 0.5 * signed_area2(ring);
  if (area_flat < 0) {
    for (Vec2& p : flat) p.y() = -p.y();
    area_flat = -area_flat;
  }
  if (!(area_flat > 0)) throw GeometryFailure("flatten: degenerate result");
  const double scale = std::sqrt(out.area_3d / area_flat);
  for (Vec2& p : flat) p *= scale;

  double sum = 0;
  int count = 0;
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k) {
      const int i = t[k], j = t[(k + 1) % 3];
      const double l3 = (xyz[i] - xyz[j]).norm();
      if (l3 <= 0) continue;
      const double e = std::abs((flat[i] - flat[j]).norm() / l3 - 1.0);
      out.strain_max = std::max(out.strain_max, e);
      sum += e;
      ++count;
    }
  out.strain_mean = count ? sum / count : 0.0;

  // Outline in the panel's own corner order.
  for (int c = 0; c < n; ++c) {
    out.corner_index.push_back(static_cast<int>(out.outline.size()));
    const Vec2 &a = corner_uv[c], &bb = corner_uv[(c + 1) % n];
    for (int k = 0; k < m; ++k) {
      const Vec2 p = a + (bb - a) * (double(k) / m);
      const std::pair<long long, long long> key{std::llround((p.x() - uv[0].x()) * key_scale),
                                                std::llround((p.y() - uv[0].y()) * key_scale)};
      auto it = index.find(key);
      if (it == index.end()) throw GeometryFailure("flatten: boundary point not in the mesh");
      out.outline.push_back(flat[it->second]);
    }
  }
  // Orientation mark: flat = A (u,v) + t by least squares; u maps along A's first column.
  Eigen::MatrixXd lm(nv, 3), lr(nv, 2);
  for (int i = 0; i < nv; ++i) {
    lm.row(i) << vuv[i].x() - uv[0].x(), vuv[i].y() - uv[0].y(), 1.0;
    lr.row(i) << flat[i].x(), flat[i].y();
  }
  const Eigen::MatrixXd fit = lm.colPivHouseholderQr().solve(lr);
  const Vec2 du(fit(0, 0), fit(0, 1));
  if (du.allFinite() && du.norm() > 0) out.u_direction = du.normalized();
  // A reversed (u,v) outline flattens mirrored relative to the panel's front.
  if (!ccw) {
    for (Vec2& p : out.outline) p.y() = -p.y();
    out.u_direction.y() = -out.u_direction.y();
  }
  // Like an unfolded panel: corner 0 at the origin, its first edge along +x.
  const Vec2 origin = out.outline[0];
  const Vec2 e =
      (out.outline[out.corner_index.size() > 1 ? out.corner_index[1] : 1] - origin).normalized();
  auto rot = [&](const Vec2& d) { return Vec2(d.dot(e), -e.y() * d.x() + e.x() * d.y()); };
  for (Vec2& p : out.outline) p = rot(p - origin);
  out.u_direction = rot(out.u_direction);
  return out;
}

std::vector<FlatPatch> flatten_panels(const SurfaceFace& face, const PanelMesh& mesh,
                                      const FlattenParams& params) {
  std::vector<FlatPatch> out;
  for (std::size_t p = 0; p < mesh.panels.size(); ++p)
    out.push_back(flatten_patch(face, panel_corner_uv(mesh, p), params));
  return out;
}

std::vector<FlatPatch> flatten_face_set_panels(const FaceSet& set, const PanelMesh& mesh,
                                               const std::vector<int>& panel_face,
                                               const FlattenParams& params) {
  if (panel_face.size() != mesh.panels.size())
    throw InvalidParameter("flatten: one face index per panel expected");
  // panel_face names faces as given; the set holds those it did not skip.
  std::vector<int> held(set.given_count(), -1);
  for (std::size_t f = 0; f < set.size(); ++f)
    held[static_cast<std::size_t>(set.given_index(f))] = static_cast<int>(f);
  std::vector<FlatPatch> out;
  out.reserve(mesh.panels.size());
  for (std::size_t p = 0; p < mesh.panels.size(); ++p) {
    const int f = panel_face[p];
    if (f < 0 || std::size_t(f) >= held.size() || held[std::size_t(f)] < 0)
      throw InvalidParameter("flatten: panel " + std::to_string(p + 1) + " names face " +
                             std::to_string(f + 1) + ", not a face of the set's " +
                             std::to_string(set.given_count()));
    out.push_back(flatten_patch(*set.face(std::size_t(held[std::size_t(f)])),
                                panel_corner_uv(mesh, p), params));
  }
  return out;
}

}  // namespace tessella
