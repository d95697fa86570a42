#include "mesh/pinned_lines.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace tessella {

void pin_lines(std::vector<double>& lines, std::vector<double> pinned) {
  std::sort(pinned.begin(), pinned.end());
  const double lo = lines.front(), hi = lines.back(), eps = 1e-9 * (hi - lo);
  std::vector<char> moved(lines.size(), 0);
  for (double c : pinned) {
    if (!(c > lo + eps && c < hi - eps)) continue;
    const auto at = std::lower_bound(lines.begin(), lines.end(), c);
    std::size_t i = static_cast<std::size_t>(at - lines.begin());
    if (i > 0 && (i == lines.size() || c - lines[i - 1] < lines[i] - c)) --i;
    if (std::abs(lines[i] - c) <= eps) {
      moved[i] = 1;
      continue;
    }
    if (i == 0 || i + 1 == lines.size() || moved[i]) {
      const std::size_t k = static_cast<std::size_t>(at - lines.begin());
      lines.insert(lines.begin() + k, c);
      moved.insert(moved.begin() + k, 1);
      continue;
    }
    lines[i] = c;  // between its neighbours: c lies nearer to it than to them
    moved[i] = 1;
  }
}

std::vector<double> lines_covering(const std::vector<double>& lines, double lo, double hi) {
  const double eps = 1e-9 * (hi - lo);
  double first = lo, last = hi;
  for (double x : lines)
    if (x <= lo + eps) first = x;
  for (auto it = lines.rbegin(); it != lines.rend(); ++it)
    if (*it >= hi - eps) last = *it;
  std::vector<double> out{first};
  for (double x : lines)
    if (x > lo + eps && x < hi - eps) out.push_back(x);
  out.push_back(last);
  return out;
}

std::vector<double> increasing_lines(const std::vector<double>& sorted, double lo, double hi) {
  const double eps = 1e-9 * (hi - lo);
  std::vector<double> out;
  for (double x : sorted)
    if (out.empty() || x - out.back() > eps) out.push_back(x);
  out.front() = lo;
  if (hi - out.back() <= eps)
    out.back() = hi;
  else
    out.push_back(hi);
  return out;
}

}  // namespace tessella
