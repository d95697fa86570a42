// The global closest-point search behind SurfaceFace::project when Newton
// fails: OCCT's Extrema over a sample grid of the search range. The grid is
// sampled once and reused for every point (rebuilt per call it cost 36 ms a
// panel on a 312 x 323-pole surface). Not thread-safe: one per thread.
#pragma once

#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_Surface.hxx>

#include "tessella/surface_face.h"

namespace tessella {

class GlobalProjection {
 public:
  GlobalProjection(const Handle(Geom_Surface) & surface, const UvBounds& range);
  GlobalProjection(const GlobalProjection&) = delete;
  GlobalProjection& operator=(const GlobalProjection&) = delete;

  // Parameters of the nearest orthogonal foot point; false if there is none
  // (or OCCT failed).
  bool nearest(const Vec3& p, Vec2& uv);

 private:
  GeomAPI_ProjectPointOnSurf projector_;
};

}  // namespace tessella
