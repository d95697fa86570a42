// Nesting flat parts on stock sheets: deterministic bottom-left placement on
// the parts' convex hulls with no-fit polygons, overlap-free by construction
// (Clipper on an integer grid of `resolution`).
#pragma once

#include <string>
#include <vector>

#include "tessella/vec.h"

namespace tessella {

struct NestParams {
  double sheet_width = 2500.0;   // mm
  double sheet_height = 1250.0;  // mm
  double margin = 10.0;          // free border on every side of the sheet (mm)
  double spacing = 6.0;          // least distance between two parts (mm)
  int rotations = 4;             // allowed rotations: multiples of 360/rotations degrees
  double resolution = 1e-3;      // integer grid step of the placement (mm)
  int max_sheets = 10000;        // refuse layouts needing more sheets
};

struct NestPlacement {
  int sheet = -1;
  double angle_deg = 0.0;  // rotation about the part's own origin, counter-clockwise
  Vec2 offset{0.0, 0.0};   // then this translation: sheet point = R(angle) p + offset
};

struct NestLayout {
  std::vector<NestPlacement> placements;  // one per part, in input order
  int sheet_count = 0;
  std::vector<double> sheet_utilization;  // part area / sheet area, per sheet
  double utilization = 0.0;               // all parts / all sheets used
};

// Nests the parts (closed outlines, any orientation, mm). `names` (optional,
// one per part) name a part in errors. Throws InvalidParameter for a bad
// setting or a part that fits the sheet in no allowed rotation.
NestLayout nest_parts(const std::vector<std::vector<Vec2>>& outlines, const NestParams& params,
                      const std::vector<std::string>& names = {});

// Convex hull, counter-clockwise, no collinear points.
std::vector<Vec2> convex_hull(std::vector<Vec2> points);

// Area of a simple polygon (positive when counter-clockwise).
double polygon_area(const std::vector<Vec2>& polygon);

}  // namespace tessella
