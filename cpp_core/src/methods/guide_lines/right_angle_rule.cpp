// The 90-degree rule connecting two neighbouring node rows into triangles
// (seed 004 section 5.1 step 8, Fig. 14).
#include "methods/guide_lines/right_angle_rule.h"

#include "methods/guide_lines/chord_division.h"
#include "tessella/guide_line_scaling.h"
#include "tessella/two_guide_lines.h"

namespace tessella {

std::vector<std::array<int, 3>> connect_rows_right_angle(const std::vector<Vec3>& p,
                                                         const std::vector<Vec3>& q) {
  std::vector<std::array<int, 3>> tris;
  const int n = static_cast<int>(p.size()), m = static_cast<int>(q.size());
  if (n == 0 || m == 0 || n + m < 3) return tris;
  int k = 0, j = 0;
  while (k < n - 1 || j < m - 1) {
    bool advance_p;
    if (k == n - 1)
      advance_p = false;  // residual Q points fan to P_{n-1}
    else if (j == m - 1)
      advance_p = true;  // residual P points fan to Q_{m-1}
    else
      // angle Q_j P_k P_{k+1} <= 90 degrees: Q_j is not behind P_k.
      advance_p = (q[j] - p[k]).dot(p[k + 1] - p[k]) >= 0.0;
    if (advance_p) {
      tris.push_back({k, k + 1, n + j});
      ++k;
    } else {
      tris.push_back({k, n + j + 1, n + j});
      ++j;
    }
  }
  return tris;
}

}  // namespace tessella
