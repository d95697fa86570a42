#include "methods/boundary_driven/bd_sources.h"

#include <algorithm>
#include <sstream>

#include "tessella/errors.h"

namespace tessella {

void finish_polyline(BdPolyline& line) {
  const std::size_t n = line.xyz.size();
  const std::size_t segs = line.closed ? n : (n > 0 ? n - 1 : 0);
  double length = 0;
  for (std::size_t i = 0; i < segs; ++i) length += (line.xyz[(i + 1) % n] - line.xyz[i]).norm();
  // A pole (a trim edge collapsed to one point in 3D but running along (u,v))
  // gets a tiny arc length in proportion to its (u,v) length, so that nodes
  // along it keep their order and stay apart (merged into one, the (u,v)
  // network would have an edge across the whole parameter range).
  const double degenerate = 1e-12 * length;
  line.arc.assign(1, 0.0);
  for (std::size_t i = 0; i < segs; ++i) {
    double l = (line.xyz[(i + 1) % n] - line.xyz[i]).norm();
    if (l <= degenerate)
      l = std::max(l, 1e-9 * length * (line.uv[(i + 1) % n] - line.uv[i]).norm());
    line.arc.push_back(line.arc.back() + l);
  }
}

int BdPolyline::segment_at(double& s) const {
  const double len = length();
  if (closed && len > 0) {
    s = std::fmod(s, len);
    if (s < 0) s += len;
  } else {
    s = std::clamp(s, 0.0, len);
  }
  auto it = std::upper_bound(arc.begin(), arc.end(), s);
  int i = static_cast<int>(it - arc.begin()) - 1;
  return std::clamp(i, 0, std::max(segment_count() - 1, 0));
}

Vec2 BdPolyline::uv_at(double s) const {
  const int i = segment_at(s);
  const double l = arc[i + 1] - arc[i];
  const double t = l > 0 ? std::clamp((s - arc[i]) / l, 0.0, 1.0) : 0.0;
  return uv[i] + t * (seg_end_uv(i) - uv[i]);
}

namespace {

// Where a closed loop starts: at its B-rep vertex of least (u, v) (any point
// where it has none). The curves are seeded along each loop from its start,
// and the first seeds win where two come close, so a start taken from the
// B-rep (the wire's first edge) made one face give two layouts: the British
// Museum roof as read and the same roof united from its four sub-surfaces
// (the same edges and vertices, its wires listed from other edges) gave 2,650
// and 2,679 panels.
std::size_t canonical_start(const TrimLoop& loop, int shift) {
  const std::size_t n = loop.uv.size();
  auto before = [&](std::size_t i, std::size_t j) {
    return loop.uv[i].x() < loop.uv[j].x() ||
           (loop.uv[i].x() == loop.uv[j].x() && loop.uv[i].y() < loop.uv[j].y());
  };
  std::vector<std::size_t> corners;
  for (std::size_t i = 0; i < n; ++i)
    if (i < loop.corner.size() && loop.corner[i]) corners.push_back(i);
  if (!corners.empty()) {
    std::sort(corners.begin(), corners.end(), before);
    return corners[static_cast<std::size_t>(shift) % corners.size()];
  }
  std::size_t least = 0;
  for (std::size_t i = 1; i < n; ++i)
    if (before(i, least)) least = i;
  return (least + static_cast<std::size_t>(shift) * n / 3) % n;
}

}  // namespace

BdSources select_bd_sources(const SurfaceFace& face, const std::vector<TrimLoop>& loops,
                            const BdSourceParams& params, int start_shift) {
  BdSources out;
  const double tiny = 1e-9 * face.model_size();
  for (std::size_t k = 0; k < loops.size(); ++k) {
    BdPolyline line;
    line.uv = loops[k].uv;
    line.xyz = loops[k].xyz;
    line.corner = loops[k].corner;
    line.corner.resize(line.uv.size(), 0);
    if (!line.uv.empty()) {
      const auto start = static_cast<long>(canonical_start(loops[k], start_shift));
      std::rotate(line.uv.begin(), line.uv.begin() + start, line.uv.end());
      std::rotate(line.xyz.begin(), line.xyz.begin() + start, line.xyz.end());
      std::rotate(line.corner.begin(), line.corner.begin() + start, line.corner.end());
    }
    line.closed = true;
    line.loop = static_cast<int>(k);
    line.outer = loops[k].outer;
    if (line.uv.size() < 3)
      throw InvalidGeometry("trim loop " + std::to_string(k) + " has fewer than 3 points");
    finish_polyline(line);
    if (line.length() <= tiny)
      throw InvalidGeometry("trim loop " + std::to_string(k) + " is degenerate (no length in 3D)");
    out.boundary.push_back(std::move(line));
  }
  if (params.loops.empty()) {
    out.sources = out.boundary;
  } else {
    for (int k : params.loops) {
      require_in_range("source loop index", k, 0, static_cast<double>(loops.size()) - 1);
      if (std::any_of(out.sources.begin(), out.sources.end(),
                      [k](const BdPolyline& l) { return l.loop == k; }))
        continue;
      out.sources.push_back(out.boundary[k]);
    }
  }
  for (std::size_t c = 0; c < params.extra_curves.size(); ++c) {
    const auto& pts = params.extra_curves[c];
    const std::string name = "extra source curve " + std::to_string(c);
    if (pts.size() < 2) throw InvalidParameter(name + " needs at least 2 (u,v) points");
    BdPolyline line;
    for (const Vec2& p : pts) {
      if (!p.allFinite() || !face.is_inside(p.x(), p.y())) {
        std::ostringstream msg;
        msg << name << ": point (" << p.x() << ", " << p.y() << ") is not inside the face";
        throw InvalidParameter(msg.str());
      }
      line.uv.push_back(p);
      line.xyz.push_back(face.point(p.x(), p.y()));
    }
    finish_polyline(line);
    if (line.length() <= tiny) throw InvalidParameter(name + " has no length");
    out.sources.push_back(std::move(line));
  }
  if (out.sources.empty()) throw InvalidParameter("no source curves selected");
  return out;
}

}  // namespace tessella

namespace tessella {

std::vector<double> bd_corners(const BdPolyline& line, double angle_deg) {
  const int n = static_cast<int>(line.xyz.size());
  const double cos_limit = std::cos(angle_deg * 3.14159265358979323846 / 180.0);
  const double tiny = 1e-12 * std::max(line.length(), 1e-300);
  std::vector<double> out;
  if (!line.closed) {
    out.push_back(0.0);
    out.push_back(line.length());
  }
  for (int i = 0; i < n; ++i) {
    if (!line.closed && (i == 0 || i == n - 1)) continue;
    // Inside a pole's stretch (both chords collapsed): not a corner; its two
    // ends are.
    if (line.collapsed((i + n - 1) % n) && line.collapsed(i)) continue;
    // previous and next non-degenerate chords
    Vec3 a = Vec3::Zero(), b = Vec3::Zero();
    for (int k = 1; k < n && a.norm() <= tiny; ++k)
      a = line.xyz[i] - line.xyz[((i - k) % n + n) % n];
    for (int k = 1; k < n && b.norm() <= tiny; ++k) b = line.xyz[(i + k) % n] - line.xyz[i];
    if (a.norm() <= tiny || b.norm() <= tiny) continue;
    if (a.normalized().dot(b.normalized()) < cos_limit) out.push_back(line.arc[i]);
  }
  std::sort(out.begin(), out.end());
  return out;
}

void bd_tangent_at(const BdPolyline& line, double s, Vec3& tangent3, Vec2& tangent_uv) {
  int i = line.segment_at(s);
  const int n = static_cast<int>(line.xyz.size());
  const int segs = line.segment_count();
  // skip zero-length segments (forward, then backward)
  int k = i;
  for (int step = 0; step < segs && line.collapsed(k); ++step) k = (k + 1) % segs;
  if (line.collapsed(k)) k = i;
  tangent3 = (line.xyz[(k + 1) % n] - line.xyz[k]).normalized();
  tangent_uv = line.seg_end_uv(k) - line.uv[k];
}

}  // namespace tessella
