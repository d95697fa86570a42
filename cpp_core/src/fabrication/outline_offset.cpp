#include "tessella/outline_offset.h"

#include <clipper.hpp>
#include <cmath>

#include "tessella/errors.h"

namespace tessella {

std::vector<Vec2> offset_outline(const std::vector<Vec2>& outline,
                                 const OutlineOffsetParams& params) {
  require_in_range("kerf offset distance (mm)", params.distance, -1e6, 1e6);
  require_in_range("resolution (mm)", params.resolution, 1e-9, 1.0);
  require_in_range("arc_tolerance (mm)", params.arc_tolerance, 1e-6, 1e3);
  if (outline.size() < 3) throw InvalidParameter("an outline needs at least 3 points");
  const double scale = 1.0 / params.resolution;
  ClipperLib::Path path;
  for (const Vec2& p : outline) {
    if (!p.allFinite()) throw InvalidParameter("outline has a non-finite point");
    path.emplace_back(static_cast<ClipperLib::cInt>(std::llround(p.x() * scale)),
                      static_cast<ClipperLib::cInt>(std::llround(p.y() * scale)));
  }
  if (!ClipperLib::Orientation(path)) ClipperLib::ReversePath(path);
  ClipperLib::ClipperOffset off(2.0, params.arc_tolerance * scale);
  off.AddPath(path, params.round_corners ? ClipperLib::jtRound : ClipperLib::jtMiter,
              ClipperLib::etClosedPolygon);
  ClipperLib::Paths result;
  off.Execute(result, params.distance * scale);
  if (result.empty()) throw InvalidParameter("the offset outline vanishes: offset too negative");
  // The largest piece (a negative offset may split a thin part).
  std::size_t best = 0;
  for (std::size_t i = 1; i < result.size(); ++i)
    if (std::abs(ClipperLib::Area(result[i])) > std::abs(ClipperLib::Area(result[best]))) best = i;
  ClipperLib::Path& r = result[best];
  if (!ClipperLib::Orientation(r)) ClipperLib::ReversePath(r);
  std::vector<Vec2> out;
  for (const auto& q : r) out.emplace_back(q.X / scale, q.Y / scale);
  return out;
}

}  // namespace tessella
