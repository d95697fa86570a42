// The 90-degree rule of seed 004 (section 5.1 step 8), private to the
// guide-line methods.
#pragma once

#include <array>
#include <vector>

#include "tessella/vec.h"

namespace tessella {

// Connects two neighbouring node rows P (curve i) and Q (curve i+1) into
// triangles by the 90-degree rule of seed 004 section 5.1 step 8: starting from
// the rod P0-Q0, Q_j is connected to the next point P_{k+1} while the angle
// Q_j P_k P_{k+1} is at most 90 degrees (Q_j is not behind P_k), else the rule
// moves on to Q_{j+1}; residual points at the end are connected to the last
// point of the other row. Triangle corners index P as 0..n-1 and Q as n..n+m-1.
std::vector<std::array<int, 3>> connect_rows_right_angle(const std::vector<Vec3>& p,
                                                         const std::vector<Vec3>& q);

}  // namespace tessella
