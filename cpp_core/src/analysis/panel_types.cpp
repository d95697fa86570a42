#include "tessella/panel_types.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <tuple>

#include "tessella/errors.h"

namespace tessella {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Edge lengths and turning angles (degrees) of one outline, corner by corner:
// length[i] = |p[i+1] - p[i]|, angle[i] = signed angle from the edge entering
// corner i to the edge leaving it.
struct Signature {
  std::vector<double> length, angle;
  double fold = 0.0;
  bool comparable = true;  // corners, finite lengths and angles: may match
};

Signature signature(const std::vector<Vec2>& p, double fold) {
  const std::size_t k = p.size();
  Signature s;
  s.fold = fold;
  s.length.resize(k);
  s.angle.resize(k);
  s.comparable = k > 0;
  for (std::size_t i = 0; i < k; ++i) {
    const Vec2& a = p[i];
    const Vec2& b = p[(i + 1) % k];
    const Vec2& z = p[(i + k - 1) % k];
    const double ex = b.x() - a.x(), ey = b.y() - a.y();
    const double px = a.x() - z.x(), py = a.y() - z.y();
    s.length[i] = std::sqrt(ex * ex + ey * ey);
    s.angle[i] = std::atan2(px * ey - py * ex, px * ex + py * ey) * (180.0 / kPi);
    if (!std::isfinite(s.length[i]) || !std::isfinite(s.angle[i])) s.comparable = false;
  }
  return s;
}

// The full match (see the header): some cyclic shift brings every length and
// angle within tolerance, and the folds agree.
bool matches(const Signature& s, const Signature& rep, const PanelTypeParams& tol) {
  if (!s.comparable || !rep.comparable) return false;
  if (std::abs(rep.fold - s.fold) > tol.angle_tol) return false;
  const std::size_t k = s.length.size();
  if (rep.length.size() != k) return false;
  for (std::size_t shift = 0; shift < k; ++shift) {
    bool all = true;
    for (std::size_t i = 0; i < k && all; ++i) {
      const std::size_t j = (i + shift) % k;
      all = std::abs(s.length[i] - rep.length[j]) <= tol.length_tol &&
            std::abs(s.angle[i] - rep.angle[j]) <= tol.angle_tol;
    }
    if (all) return true;
  }
  return false;
}

// Cell of a value on a grid of spacing h >= 1.5 x tolerance: values within
// tolerance lie in the same or neighbouring cells (the spacing keeps a third
// of a cell for rounding; |x/h| stays below about 1e9).
std::int64_t cell(double x, double h) { return static_cast<std::int64_t>(std::floor(x / h)); }

// The spacing for values of magnitude up to `largest` compared within `tol`.
double spacing(double tol, double largest) { return std::max({1.5 * tol, 1e-9 * largest, 1e-300}); }

// Representatives indexed by (corners, longest edge cell, shortest edge cell,
// fold cell). A non-finite fold compares as "not farther than the
// tolerance" with anything, so it gets the wildcard fold cell, which every
// lookup visits.
using Key = std::tuple<std::size_t, std::int64_t, std::int64_t, std::int64_t>;
constexpr std::int64_t kAnyFold = std::numeric_limits<std::int64_t>::min();

}  // namespace

PanelTypes panel_types(const std::vector<std::vector<Vec2>>& outlines,
                       const std::vector<double>& fold_deg, const PanelTypeParams& params) {
  require_in_range("length_tol (mm)", params.length_tol, 0.0, 1e9);
  require_in_range("angle_tol (deg)", params.angle_tol, 0.0, 360.0);
  if (outlines.size() != fold_deg.size())
    throw InvalidParameter("panel types: one fold angle per outline is needed");
  const std::size_t n = outlines.size();
  std::vector<Signature> sig;
  sig.reserve(n);
  double longest = 0.0, largest_fold = 0.0;
  for (std::size_t p = 0; p < n; ++p) {
    sig.push_back(signature(outlines[p], fold_deg[p]));
    if (!sig.back().comparable) continue;
    for (double l : sig.back().length) longest = std::max(longest, l);
    if (std::isfinite(fold_deg[p])) largest_fold = std::max(largest_fold, std::abs(fold_deg[p]));
  }
  const double hl = spacing(params.length_tol, longest);
  const double hf = spacing(params.angle_tol, largest_fold);

  PanelTypes out;
  out.type.assign(n, -1);
  std::map<Key, std::vector<int>> index;  // key -> types, increasing
  std::vector<int> candidates;
  for (std::size_t p = 0; p < n; ++p) {
    const Signature& s = sig[p];
    int found = -1;
    Key key{};
    if (s.comparable) {
      const auto [lo, hi] = std::minmax_element(s.length.begin(), s.length.end());
      const std::size_t k = s.length.size();
      const std::int64_t cmax = cell(*hi, hl), cmin = cell(*lo, hl);
      const bool any_fold = !std::isfinite(s.fold);
      const std::int64_t cfold = any_fold ? kAnyFold : cell(s.fold, hf);
      key = Key{k, cmax, cmin, cfold};
      candidates.clear();
      auto take = [&](const Key& from, const Key& to) {  // every key in [from, to]
        for (auto it = index.lower_bound(from); it != index.end() && !(to < it->first); ++it)
          candidates.insert(candidates.end(), it->second.begin(), it->second.end());
      };
      for (std::int64_t a = cmax - 1; a <= cmax + 1; ++a) {
        for (std::int64_t b = cmin - 1; b <= cmin + 1; ++b) {
          if (any_fold) {  // every fold cell
            take(Key{k, a, b, kAnyFold}, Key{k, a, b, std::numeric_limits<std::int64_t>::max()});
            continue;
          }
          take(Key{k, a, b, kAnyFold}, Key{k, a, b, kAnyFold});
          take(Key{k, a, b, cfold - 1}, Key{k, a, b, cfold + 1});
        }
      }
      // The first type (lowest index) that matches, as a scan of every type would find.
      std::sort(candidates.begin(), candidates.end());
      for (int t : candidates) {
        if (matches(s, sig[static_cast<std::size_t>(out.representative[t])], params)) {
          found = t;
          break;
        }
      }
    }
    if (found < 0) {
      found = out.count();
      out.representative.push_back(static_cast<int>(p));
      if (s.comparable) index[key].push_back(found);  // others match nothing
    }
    out.type[p] = found;
  }
  return out;
}

double type_fold_angle(const FlatPanel& flat) {
  double fold = 0.0;
  for (const Fold& f : flat.folds) fold = std::max(fold, std::abs(f.angle_deg));
  return fold;
}

PanelTypes panel_types(const std::vector<FlatPanel>& flat, const PanelTypeParams& params) {
  std::vector<std::vector<Vec2>> outlines;
  std::vector<double> folds;
  outlines.reserve(flat.size());
  folds.reserve(flat.size());
  for (const FlatPanel& f : flat) {
    outlines.push_back(f.outline);
    folds.push_back(type_fold_angle(f));
  }
  return panel_types(outlines, folds, params);
}

PanelTypes panel_types(const PanelMesh& mesh, const UnfoldParams& unfold,
                       const PanelTypeParams& params) {
  return panel_types(unfold_panels(mesh, unfold), params);
}

}  // namespace tessella
