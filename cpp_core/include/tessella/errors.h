// Typed exceptions of the core. The binding maps them to Python exceptions:
// InvalidParameter -> ValueError, InvalidGeometry -> ValueError,
// LimitExceeded -> ValueError, GeometryFailure -> RuntimeError.
#pragma once

#include <stdexcept>
#include <string>

namespace tessella {

// A parameter is out of its accepted range; the message names it and the range.
struct InvalidParameter : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// The input shape cannot be used (not a face, degenerate, unreadable BRep...).
struct InvalidGeometry : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// A face that encloses no area (a slit: its parameter range is empty in
// one direction, or its area vanishes against its size). A face set leaves
// such a face out (there is nothing to panel) instead of refusing the set.
struct FaceWithoutArea : InvalidGeometry {
  using InvalidGeometry::InvalidGeometry;
};

// The requested result would be too large (e.g. more panels than the cap).
struct LimitExceeded : std::length_error {
  using std::length_error::length_error;
};

// A geometric computation failed unexpectedly (OCCT error, no convergence).
struct GeometryFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws InvalidParameter("<name> must be in [lo, hi], got v") unless lo <= v <= hi
// (and v is finite).
void require_in_range(const char* name, double value, double lo, double hi);

}  // namespace tessella
