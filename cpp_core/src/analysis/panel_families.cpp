#include "tessella/panel_families.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <numeric>
#include <queue>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>

#include "tessella/errors.h"

namespace tessella {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A panel ready for comparisons: corners about their centroid, the table of
// corner-to-corner distances and its sorted list (both invariant under rigid
// motions), and its diameter (largest corner distance).
struct Prepared {
  std::vector<Vec3> p;        // corners minus centroid
  std::vector<double> d;      // k x k corner distances
  std::vector<double> dsort;  // the k(k-1)/2 distances i < j, increasing
  double diameter = 0.0;
  double spread = 0.0;  // sum of the squared distances of the corners to the centroid
  std::size_t k() const { return p.size(); }
};

Prepared prepare(const std::vector<Vec3>& corners) {
  Prepared out;
  const std::size_t k = corners.size();
  Vec3 c = Vec3::Zero();
  for (const Vec3& q : corners) c += q;
  c /= static_cast<double>(k);
  out.p.reserve(k);
  for (const Vec3& q : corners) {
    out.p.push_back(q - c);
    out.spread += out.p.back().squaredNorm();
  }
  out.d.assign(k * k, 0.0);
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t j = i + 1; j < k; ++j) {
      const double dij = (out.p[i] - out.p[j]).norm();
      out.d[i * k + j] = out.d[j * k + i] = dij;
      out.dsort.push_back(dij);
    }
  std::sort(out.dsort.begin(), out.dsort.end());
  out.diameter = out.dsort.empty() ? 0.0 : out.dsort.back();
  return out;
}

// Room for rounding in the necessary conditions (they must never reject a
// pair the full test would accept).
double slack(const Prepared& a, const Prepared& b) {
  return 1e-9 * (a.diameter + b.diameter) + 1e-12;
}

// Necessary condition of distance <= limit: corners within `limit` of each
// other under a rigid motion keep every corner distance within 2 x limit,
// and so (sorting is 1-Lipschitz in the max norm) the sorted lists too.
bool may_match(const Prepared& a, const Prepared& b, double limit) {
  if (a.k() != b.k()) return false;
  const double bound = 2.0 * limit + slack(a, b);
  if (std::abs(a.diameter - b.diameter) > bound) return false;
  for (std::size_t i = 0; i < a.dsort.size(); ++i)
    if (std::abs(a.dsort[i] - b.dsort[i]) > bound) return false;
  return true;
}

// The largest eigenvalue of Horn's 4x4 key matrix of the correlation matrix
// h: the largest sum sigma1 + sigma2 + det-sign * sigma3 a rotation reaches
// (Theobald's QCP: Newton on the characteristic polynomial from `start`, an
// upper bound of it). Newton from above approaches the root from above, so the
// value returned is >= the eigenvalue up to rounding.
double largest_key_eigenvalue(const Eigen::Matrix3d& h, double start) {
  const double sxx = h(0, 0), sxy = h(0, 1), sxz = h(0, 2);
  const double syx = h(1, 0), syy = h(1, 1), syz = h(1, 2);
  const double szx = h(2, 0), szy = h(2, 1), szz = h(2, 2);
  Eigen::Matrix4d n;
  n << sxx + syy + szz, syz - szy, szx - sxz, sxy - syx,  //
      syz - szy, sxx - syy - szz, sxy + syx, szx + sxz,   //
      szx - sxz, sxy + syx, -sxx + syy - szz, syz + szy,  //
      sxy - syx, szx + sxz, syz + szy, -sxx - syy + szz;
  const Eigen::Matrix4d n2 = n * n;
  const double c2 = -0.5 * n2.trace(), c1 = -n2.cwiseProduct(n).sum() / 3.0;
  const double c0 = n.determinant();
  double x = start;
  for (int it = 0; it < 60; ++it) {
    const double x2 = x * x;
    const double f = (x2 + c2) * x2 + c1 * x + c0;
    const double df = (4.0 * x2 + 2.0 * c2) * x + c1;
    if (!(df > 0.0)) break;
    const double step = f / df;
    x -= step;
    if (std::abs(step) <= 1e-12 * start) break;
  }
  return x;
}

// Largest corner distance after the Kabsch alignment of b (corner sigma[i]
// onto a's corner i) onto a: the rotation (or, with `reflect`, any orthogonal
// map) that minimises the RMS corner distance about the centroids. This is an
// upper bound of the minimax distance over rigid motions (Kabsch minimises the
// RMS, not the largest distance), which keeps the tolerance guaranteed.
//
// `cap`: when even the RMS distance of the best alignment exceeds it (so the
// largest distance does too), +infinity is returned without the SVD. The
// RMS comes from the key matrix's largest eigenvalue (cheap); a margin covers
// its rounding, so an alignment within `cap` is never missed.
double kabsch_max(const Prepared& a, const Prepared& b, const std::vector<std::size_t>& sigma,
                  bool reflect, double cap = kInf) {
  const std::size_t k = a.k();
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < k; ++i) h += b.p[sigma[i]] * a.p[i].transpose();
  if (std::isfinite(cap)) {
    const double g = a.spread + b.spread;
    double lambda = largest_key_eigenvalue(h, 0.5 * g);
    if (reflect) {  // b mirrored: its z row negated
      Eigen::Matrix3d m = h;
      m.row(2) = -m.row(2);
      lambda = std::max(lambda, largest_key_eigenvalue(m, 0.5 * g));
    }
    const double rms2 = (g - 2.0 * lambda) / static_cast<double>(k);
    if (rms2 > cap * cap + 1e-7 * g / static_cast<double>(k)) return kInf;
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d v = svd.matrixV();
  const Eigen::Matrix3d& u = svd.matrixU();
  Eigen::Matrix3d r = v * u.transpose();
  if (!reflect && r.determinant() < 0.0) {
    v.col(2) = -v.col(2);  // least singular direction flipped: the best rotation
    r = v * u.transpose();
  }
  double worst = 0.0;
  for (std::size_t i = 0; i < k; ++i)
    worst = std::max(worst, (r * b.p[sigma[i]] - a.p[i]).squaredNorm());
  return std::sqrt(worst);
}

// Distance of b to a (see the header), considering only the correspondences
// that pass the necessary condition for `limit` (+infinity if none does).
// A correspondence whose corner distances differ by up to `mismatch` cannot
// align closer than mismatch / 2 (triangle inequality), so correspondences
// are tried by increasing mismatch and the search stops once that lower bound
// exceeds the best distance found: the result is the same as trying them all.
// With `first_within`, the first alignment within `limit` is taken (cheaper;
// still an upper bound of the minimax distance).
double distance(const Prepared& a, const Prepared& b, bool mirror, double limit,
                bool first_within = false) {
  const std::size_t k = a.k();
  if (b.k() != k) return kInf;
  const double room = slack(a, b);
  const double bound = 2.0 * limit + room;
  auto corner = [k](std::size_t c, std::size_t i) {  // correspondence c: b's corner for a's i
    const std::size_t s = c % k;
    return c < k ? (i + s) % k : (s + k - i) % k;
  };
  std::vector<std::pair<double, std::size_t>> tries;  // (mismatch, correspondence)
  const std::size_t count = mirror ? 2 * k : k;
  for (std::size_t c = 0; c < count; ++c) {
    double mismatch = 0.0;
    for (std::size_t i = 0; i < k && mismatch <= bound; ++i)
      for (std::size_t j = i + 1; j < k; ++j)
        mismatch =
            std::max(mismatch, std::abs(a.d[i * k + j] - b.d[corner(c, i) * k + corner(c, j)]));
    if (mismatch <= bound) tries.emplace_back(mismatch, c);
  }
  std::sort(tries.begin(), tries.end());
  std::vector<std::size_t> sigma(k);
  double best = kInf;
  for (const auto& [mismatch, c] : tries) {
    if (mismatch > 2.0 * best + room) break;
    for (std::size_t i = 0; i < k; ++i) sigma[i] = corner(c, i);
    best = std::min(best, kabsch_max(a, b, sigma, mirror, std::min(limit, best)));
    if (first_within && best <= limit) break;
  }
  return best;
}

void check_panels(const std::vector<std::vector<Vec3>>& panels) {
  for (std::size_t p = 0; p < panels.size(); ++p) {
    if (panels[p].size() < 3) {
      std::ostringstream msg;
      msg << "panel families: panel " << p << " has " << panels[p].size()
          << " corners, at least 3 are needed";
      throw InvalidGeometry(msg.str());
    }
    for (const Vec3& q : panels[p])
      if (!q.allFinite()) {
        std::ostringstream msg;
        msg << "panel families: panel " << p << " has a non-finite corner coordinate";
        throw InvalidGeometry(msg.str());
      }
  }
}

// A neighbour within the tolerance and its distance.
using Neighbour = std::pair<int, double>;

}  // namespace

double panel_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b, bool mirror) {
  check_panels({a, b});
  if (a.size() != b.size()) return kInf;
  return distance(prepare(a), prepare(b), mirror, kInf);
}

PanelFamilies panel_families(const std::vector<std::vector<Vec3>>& panels,
                             const PanelFamilyParams& params) {
  const double tol = params.tolerance;
  if (!(std::isfinite(tol) && tol > 0.0 && tol <= 1e9)) {
    std::ostringstream msg;
    msg << "family_tolerance (mm) must be > 0 and at most 1e9, got " << tol;
    throw InvalidParameter(msg.str());
  }
  if (params.max_pairs < 0)
    throw InvalidParameter("max_pairs must be >= 0 (0 = automatic), got " +
                           std::to_string(params.max_pairs));
  check_panels(panels);
  const bool mirror = params.mirror;
  const int n = static_cast<int>(panels.size());
  std::vector<Prepared> prep;
  prep.reserve(panels.size());
  for (const auto& corners : panels) prep.push_back(prepare(corners));

  // Panels in order of (corners, diameter, index): candidates of a panel are
  // a window of this order.
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int x, int y) {
    return std::make_tuple(prep[x].k(), prep[x].diameter, x) <
           std::make_tuple(prep[y].k(), prep[y].diameter, y);
  });

  // 1. Twins: panels within eps of a lower-indexed leader (repeated panels: a
  // flat grid, the rows of a surface of revolution) are handled as their
  // leader, so n identical panels cost n comparisons, not n^2. Leaders then
  // cover each other within tol - eps, so a twin is within tol of its
  // template through its leader (the composed alignment is a rigid motion).
  // eps is 1e-3 x tol; when that leaves more candidate pairs among leaders
  // than `budget` (a tolerance far above the panels' differences: nearly all
  // pairs are within reach), eps grows (tol / 32 ... tol / 4), which keeps the
  // cost near linear at the price of a cover at tol - eps among leaders.
  std::vector<int> leader(n, -1);
  std::vector<double> twin_dist(n, 0.0);  // distance to its leader
  auto group_twins = [&](double eps) {
    // Leaders so far by (corner count, diameter): a panel looks only at those
    // whose diameter is within 2 eps of its own (with room for rounding).
    std::multimap<std::pair<std::size_t, double>, int> seen;
    for (int p = 0; p < n; ++p) {  // index order: a leader is its group's lowest index
      const Prepared& a = prep[p];
      const double w = 2.0 * eps + 3e-9 * (a.diameter + eps) + 1e-12;
      int found = -1;
      double found_d = 0.0;
      const auto end = seen.upper_bound({a.k(), a.diameter + w});
      for (auto it = seen.lower_bound({a.k(), a.diameter - w}); it != end; ++it) {
        const int q = it->second;
        if ((found >= 0 && q > found) || !may_match(prep[q], a, eps)) continue;
        const double dq = distance(prep[q], a, mirror, eps, true);
        if (dq <= eps) found = q, found_d = dq;
      }
      leader[p] = found < 0 ? p : found;
      twin_dist[p] = found < 0 ? 0.0 : found_d;
      if (found < 0) seen.emplace(std::make_pair(a.k(), a.diameter), p);
    }
  };
  // Calls f(a, b) for each pair of leaders (in `order`) passing the cheap
  // necessary conditions of distance <= limit; stops when f returns false.
  auto candidate_pairs = [&](double limit, auto&& f) {
    std::vector<int> lorder;  // leaders in `order`
    for (int p : order)
      if (leader[p] == p) lorder.push_back(p);
    for (std::size_t r = 0; r < lorder.size(); ++r) {
      const Prepared& a = prep[lorder[r]];
      for (std::size_t s = r + 1; s < lorder.size(); ++s) {
        const Prepared& b = prep[lorder[s]];
        if (b.k() != a.k() || b.diameter - a.diameter > 2.0 * limit + slack(a, b)) break;
        if (may_match(a, b, limit) && !f(lorder[r], lorder[s])) return;
      }
    }
  };
  // The twin radius: the smallest of these that leaves at most `budget`
  // candidate pairs among the leaders (counting stops at the budget).
  const long long budget = params.max_pairs > 0 ? params.max_pairs : std::max(400000LL, 64LL * n);
  double eps = 0.0;
  for (double fraction : {1e-3, 1.0 / 32, 1.0 / 16, 1.0 / 8, 1.0 / 4}) {
    eps = fraction * tol;
    group_twins(eps);
    long long pairs = 0;
    candidate_pairs(tol - eps, [&](int, int) { return ++pairs <= budget; });
    if (pairs <= budget) break;
  }
  const double tol_eff = tol - eps;
  std::vector<int> leaders;  // increasing index
  for (int p = 0; p < n; ++p)
    if (leader[p] == p) leaders.push_back(p);
  const int m = static_cast<int>(leaders.size());
  std::vector<int> slot(n, -1);  // leader panel -> its position in `leaders`
  for (int i = 0; i < m; ++i) slot[leaders[i]] = i;
  std::vector<double> weight(m, 0.0), radius(m, 0.0);  // twins per leader, largest twin distance
  for (int p = 0; p < n; ++p) {
    const int i = slot[leader[p]];
    weight[i] += 1.0;
    radius[i] = std::max(radius[i], twin_dist[p]);
  }

  // 2. Leaders within tol_eff of each other (symmetric, each pair measured
  // once, from the lower index, so the value does not depend on the order).
  // The first alignment found within tol_eff is kept (an upper bound like any
  // other; the final errors take the best one).
  std::vector<std::vector<Neighbour>> adj(m);
  candidate_pairs(tol_eff, [&](int pa, int pb) {
    const int lo = std::min(pa, pb), hi = std::max(pa, pb);
    const double d = distance(prep[lo], prep[hi], mirror, tol_eff, true);
    if (d <= tol_eff) {
      adj[slot[lo]].emplace_back(slot[hi], d);
      adj[slot[hi]].emplace_back(slot[lo], d);
    }
    return true;
  });
  for (auto& list : adj) std::sort(list.begin(), list.end());
  // Distance between leaders i and j if within tol_eff (0 for i == j), else +inf.
  auto dist = [&](int i, int j) {
    if (i == j) return 0.0;
    const auto it = std::lower_bound(adj[i].begin(), adj[i].end(), Neighbour(j, -kInf));
    return it != adj[i].end() && it->first == j ? it->second : kInf;
  };

  // 3. Greedy set cover with lazy gains (gains only decrease): the leader
  // covering the most uncovered panels, ties by lowest index.
  std::vector<char> covered(m, 0);
  std::vector<int> chosen;
  {
    auto gain = [&](int i) {
      double g = covered[i] ? 0.0 : weight[i];
      for (const Neighbour& nb : adj[i])
        if (!covered[nb.first]) g += weight[nb.first];
      return g;
    };
    using Entry = std::pair<double, int>;  // (gain, -index): largest gain, then lowest index
    std::priority_queue<Entry> heap;
    for (int i = 0; i < m; ++i) heap.emplace(gain(i), -i);
    int left = m;
    while (left > 0 && !heap.empty()) {
      const Entry top = heap.top();
      heap.pop();
      const int i = -top.second;
      const Entry now(gain(i), -i);
      if (now.first <= 0.0) continue;
      if (!heap.empty() && now < heap.top()) {
        heap.push(now);
        continue;
      }
      chosen.push_back(i);
      if (!covered[i]) covered[i] = 1, --left;
      for (const Neighbour& nb : adj[i])
        if (!covered[nb.first]) covered[nb.first] = 1, --left;
    }
  }
  // Redundant templates: one whose every covered leader (itself included) is
  // also covered by another template goes, the last chosen first (they
  // covered the fewest new panels). Templates chosen later can make earlier
  // ones redundant; this never uncovers a leader.
  {
    std::vector<int> cover_count(m, 0);
    auto each_covered = [&](int t, auto&& f) {
      f(t);
      for (const Neighbour& nb : adj[t]) f(nb.first);
    };
    for (int t : chosen) each_covered(t, [&](int i) { ++cover_count[i]; });
    std::vector<int> kept;
    std::vector<char> drop(chosen.size(), 0);
    for (std::size_t c = chosen.size(); c-- > 0;) {
      bool redundant = true;
      each_covered(chosen[c], [&](int i) { redundant = redundant && cover_count[i] >= 2; });
      if (redundant) {
        drop[c] = 1;
        each_covered(chosen[c], [&](int i) { --cover_count[i]; });
      }
    }
    for (std::size_t c = 0; c < chosen.size(); ++c)
      if (!drop[c]) kept.push_back(chosen[c]);
    chosen.swap(kept);

    // 2-for-1 swaps: two templates whose exclusive panels (covered by no
    // other template) one panel covers all of are replaced by that panel
    // (the lowest index), templates in increasing order, until none applies
    // or the work bound is spent (the same for the same input).
    std::vector<char> is_t(m, 0);
    for (int t : chosen) is_t[t] = 1;
    auto covers = [&](int c, int i) { return c == i || dist(c, i) <= tol_eff; };
    long long work = 0;
    const long long work_bound = 40LL * budget;
    std::vector<int> partners, exclusive;
    for (bool improved = true; improved && work < work_bound;) {
      improved = false;
      for (int t1 = 0; t1 < m && work < work_bound; ++t1) {
        if (!is_t[t1]) continue;
        partners.clear();
        each_covered(t1, [&](int i) {
          each_covered(i, [&](int t2) {
            if (is_t[t2] && t2 != t1) partners.push_back(t2);
          });
        });
        work += static_cast<long long>(partners.size());
        std::sort(partners.begin(), partners.end());
        partners.erase(std::unique(partners.begin(), partners.end()), partners.end());
        for (int t2 : partners) {
          exclusive.clear();
          each_covered(t1, [&](int i) {
            if (cover_count[i] == 1 + (covers(t2, i) ? 1 : 0)) exclusive.push_back(i);
          });
          each_covered(t2, [&](int i) {
            if (cover_count[i] == 1 && !covers(t1, i)) exclusive.push_back(i);
          });
          work += static_cast<long long>(adj[t1].size() + adj[t2].size());
          if (exclusive.empty()) continue;
          int found = -1;
          each_covered(exclusive[0], [&](int c) {
            if (c == t1 || c == t2 || (found >= 0 && c > found)) return;
            work += static_cast<long long>(exclusive.size());
            for (int u : exclusive)
              if (!covers(c, u)) return;
            found = c;
          });
          if (found < 0) continue;
          is_t[t1] = is_t[t2] = 0;
          each_covered(t1, [&](int i) { --cover_count[i]; });
          each_covered(t2, [&](int i) { --cover_count[i]; });
          if (!is_t[found]) {
            is_t[found] = 1;
            each_covered(found, [&](int i) { ++cover_count[i]; });
          }
          improved = true;
          break;
        }
      }
    }
    chosen.clear();
    for (int i = 0; i < m; ++i)
      if (is_t[i]) chosen.push_back(i);
  }

  // 4. Each leader joins its nearest template; each family's template becomes
  // the member leader whose worst distance to the family (twins counted with
  // their distance to their leader) is least; repeat until stable.
  const int f_count = static_cast<int>(chosen.size());
  std::vector<int> tmpl = chosen;  // per family: template leader
  std::vector<int> family(m, -1);  // per leader
  for (int round = 0; round < 16; ++round) {
    std::vector<int> is_template(m, -1);
    for (int f = 0; f < f_count; ++f) is_template[tmpl[f]] = f;
    for (int i = 0; i < m; ++i) {
      if (is_template[i] >= 0) {
        family[i] = is_template[i];
        continue;
      }
      int best = -1;
      double best_d = kInf;
      for (const Neighbour& nb : adj[i]) {  // templates within tolerance of i
        const int f = is_template[nb.first];
        if (f >= 0 && (nb.second < best_d || (nb.second == best_d && f < best)))
          best = f, best_d = nb.second;
      }
      family[i] = best;  // always found: the cover stays valid
    }
    std::vector<std::vector<int>> members(f_count);
    for (int i = 0; i < m; ++i) members[family[i]].push_back(i);
    bool changed = false;
    for (int f = 0; f < f_count; ++f) {
      int best = tmpl[f];
      double best_w = kInf;
      for (int c : members[f]) {  // increasing index: ties keep the lowest
        double w = 0.0;
        for (int x : members[f]) {
          w = std::max(w, dist(c, x) + radius[x]);
          if (w >= best_w) break;
        }
        if (w < best_w) best = c, best_w = w;
      }
      if (best != tmpl[f]) tmpl[f] = best, changed = true;
    }
    if (!changed) break;
  }

  // 5. Per panel: the family of its leader, its error against the template
  // (the direct alignment, or the composed one through its leader if that is
  // better: both are rigid alignments).
  std::vector<int> family_of_panel(n);
  for (int p = 0; p < n; ++p) family_of_panel[p] = family[slot[leader[p]]];
  // Families numbered by their lowest panel index.
  std::vector<int> number(f_count, -1);
  int next = 0;
  for (int p = 0; p < n; ++p)
    if (number[family_of_panel[p]] < 0) number[family_of_panel[p]] = next++;
  PanelFamilies out;
  out.twin_radius = eps;
  out.labels.resize(n);
  out.error.resize(n);
  out.templates.assign(f_count, -1);
  out.max_error.assign(f_count, 0.0);
  for (int f = 0; f < f_count; ++f) out.templates[number[f]] = leaders[tmpl[f]];
  for (int p = 0; p < n; ++p) {
    const int f = number[family_of_panel[p]];
    out.labels[p] = f;
    const int t = out.templates[f];
    double e = 0.0;
    if (p != t) {
      const double through = dist(tmpl[family_of_panel[p]], slot[leader[p]]) + twin_dist[p];
      e = std::min(distance(prep[t], prep[p], mirror, kInf), through);
    }
    out.error[p] = e;
    out.max_error[f] = std::max(out.max_error[f], e);
  }
  return out;
}

}  // namespace tessella
