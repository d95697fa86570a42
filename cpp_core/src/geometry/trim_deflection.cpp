#include "geometry/trim_deflection.h"

namespace tessella {

double automatic_trim_deflection(const SurfaceFace& face) {
  return kAutomaticTrimDeflection * face.model_size();
}

double trim_deflection(const SurfaceFace& face, double requested) {
  return requested > 0 ? requested : automatic_trim_deflection(face);
}

double steering_trim_deflection(const SurfaceFace& face) {
  return kSteeringTrimDeflection * face.model_size();
}

}  // namespace tessella
