#include "faceset/shared_edge_check.h"

#include <Geom2d_Curve.hxx>
#include <algorithm>
#include <map>
#include <utility>

#include "geometry/edge_track.h"
#include "tessella/surface_face.h"

namespace tessella {

SharedEdgeCheck check_shared_edges(const FaceSet::Impl& set, const PanelMesh& mesh,
                                   const std::vector<int>& panel_face) {
  SharedEdgeCheck check;
  if (set.shared.empty()) return check;
  // On the edge: within twice the join's match tolerance (1e-6 of a face's
  // size) of its curve. Farther, a node is a trim's that merely passes
  // near (a hole grazing a cut line within 0.07 mm).
  const double tol = 2e-6 * set.model_size;
  // Each panel side (by its end vertices) with the faces of the panels on it.
  std::map<std::pair<int, int>, std::vector<int>> sides;
  for (std::size_t p = 0; p < mesh.panels.size(); ++p) {
    const std::vector<int>& q = mesh.panels[p];
    for (std::size_t i = 0; i < q.size(); ++i) {
      const int a = q[i], b = q[(i + 1) % q.size()];
      sides[{std::min(a, b), std::max(a, b)}].push_back(panel_face[p]);
    }
  }
  std::vector<int> nodes;
  for (int v = 0; v < static_cast<int>(mesh.vertex_count()); ++v)
    if (is_node(mesh, v)) nodes.push_back(v);
  for (const SharedEdge& e : set.shared) {
    const SurfaceFace& face = *set.faces[static_cast<std::size_t>(e.faces[0])];
    const Handle(Geom2d_Curve)& curve = e.pcurve[0];
    auto at = [&](double t) {
      const gp_Pnt2d q = curve->Value(t);
      return face.point(q.X(), q.Y());
    };
    double sag = 0;
    const EdgeTrack track(sample_curve(at, e.first, e.last, tol, 4096, sag));
    const double reach = tol + sag;
    double x0 = 0, y0 = 0, z0 = 0, x1 = 0, y1 = 0, z1 = 0;
    if (!e.box.IsVoid()) e.box.Get(x0, y0, z0, x1, y1, z1);
    // The nodes on the edge, in order along it (polyline segment, fraction).
    std::vector<std::pair<double, int>> on;
    for (int v : nodes) {
      const Vec3& x = mesh.xyz[static_cast<std::size_t>(v)];
      if (!e.box.IsVoid() && (x.x() < x0 - reach || x.x() > x1 + reach || x.y() < y0 - reach ||
                              x.y() > y1 + reach || x.z() < z0 - reach || x.z() > z1 + reach))
        continue;
      std::size_t segment = 0;
      double fraction = 0;
      if (track.nearest(x, reach, segment, fraction))
        on.push_back({static_cast<double>(segment) + fraction, v});
    }
    std::sort(on.begin(), on.end());
    const std::size_t n = on.size();
    const std::size_t segments = e.closed ? (n > 2 ? n : 0) : (n > 0 ? n - 1 : 0);
    std::array<int, 2> want = e.faces;
    std::sort(want.begin(), want.end());
    for (std::size_t k = 0; k < segments; ++k) {
      const int a = on[k].second, b = on[(k + 1) % n].second;
      ++check.segments;
      const auto it = sides.find({std::min(a, b), std::max(a, b)});
      bool fine = false;
      if (it != sides.end() && it->second.size() == 2) {
        std::array<int, 2> got{it->second[0], it->second[1]};
        std::sort(got.begin(), got.end());
        fine = got == want;
      }
      if (fine) continue;
      if (check.unmatched++ == 0) {
        check.first_at =
            0.5 * (mesh.xyz[static_cast<std::size_t>(a)] + mesh.xyz[static_cast<std::size_t>(b)]);
        check.first_faces = e.faces;
      }
    }
  }
  return check;
}

}  // namespace tessella
