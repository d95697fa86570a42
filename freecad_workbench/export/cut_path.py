"""Cut paths for CAM: a closed outline simplified and fitted with arcs (pure numpy).

    from freecad_workbench.export.cut_path import make_cut_path
    path = make_cut_path(outline, simplify_tolerance=1e-3, chord_tolerance=0.05,
                         arcs=True, keep=(0, 5))
    path.points, path.bulges, path.source   # LWPOLYLINE vertices, bulge per segment, input index
    path.segment_count                      # lines + arcs (an arc counts once)

Two steps, both deterministic and both keeping every vertex they keep exactly
where it was (no point is ever moved):

1. `simplify`: sub-micron jogs (runs of points closer than the tolerance to
   each other) collapse onto one of their points (a kept index if there is one,
   else the point where the path turns most, i.e. the corner), then points are
   removed while every input point stays within the tolerance of the path (the
   cheapest removal first; collinear points cost 0).
2. `fit_arcs`: between breakpoints (kept indices and corners, where the path
   turns by more than `corner_angle`), the longest run of vertices from the
   current vertex that one circular arc (through the run's two end vertices)
   follows within the chord tolerance becomes that arc (an LWPOLYLINE bulge);
   runs are grown greedily, at least `min_arc_segments` segments, never over a
   segment much longer than the run's others (a straight edge stays straight).
   The arc is checked against the polyline both ways: every vertex of the run is
   within the tolerance of the circle, every polyline segment bends inward from it
   by at most the tolerance, and the vertices advance monotonically along the arc.

Bulge convention (DXF): b = tan(sweep/4), positive = counter-clockwise from the
segment's start to its end; |b| <= 1 (at most a half circle per arc).
"""

import heapq
import math
from dataclasses import dataclass

import numpy as np

DEFAULT_SIMPLIFY_TOLERANCE = 1e-3  # mm
DEFAULT_CHORD_TOLERANCE = 0.05  # mm
DEFAULT_CORNER_ANGLE = 30.0  # degrees of turning that make a vertex a corner
DEFAULT_MIN_ARC_SEGMENTS = 3
DEFAULT_LENGTH_RATIO = 4.0  # a segment longer than this times the run's median ends the run


@dataclass
class CutPath:
    """A closed path: vertex k, then a line (bulge 0) or an arc (bulge != 0) to vertex k+1."""

    points: np.ndarray  # (m,2)
    bulges: np.ndarray  # (m,) bulge of the segment from vertex k to vertex (k+1) % m
    source: np.ndarray  # (m,) index of vertex k in the input outline

    @property
    def segment_count(self):
        return int(len(self.points))

    @property
    def arc_count(self):
        return int(np.count_nonzero(self.bulges))

    def transformed(self, x, y, angle_deg):
        """The path turned by angle_deg about the origin and moved by (x, y) (bulges are
        kept: a rotation does not mirror)."""
        a = math.radians(angle_deg)
        rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        return CutPath(self.points @ rot.T + np.array([x, y]), self.bulges.copy(), self.source.copy())

    def lwpolyline_points(self):
        """[(x, y, start_width, end_width, bulge)] for ezdxf's add_lwpolyline(format="xyseb")."""
        return [(float(p[0]), float(p[1]), 0.0, 0.0, float(b)) for p, b in zip(self.points, self.bulges)]

    def sample(self, max_step=1.0):
        """Points along the path (arcs sampled at most max_step apart), closed ring."""
        return sample_path(self.points, self.bulges, max_step)


def _as_points(points):
    p = np.asarray(points, dtype=float)
    if p.ndim != 2 or p.shape[1] != 2 or len(p) < 3:
        raise ValueError(f"an outline needs at least 3 points (k,2), got shape {p.shape}")
    if not np.all(np.isfinite(p)):
        raise ValueError("an outline holds a non-finite coordinate")
    return p


def _check_tolerance(name, value):
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not (math.isfinite(v) and v >= 0.0):
        raise ValueError(f"{name} must be >= 0, got {value!r}")
    return v


def _keep_set(keep, n):
    out = set()
    for k in keep or ():
        k = int(k)
        if not -n <= k < n:
            raise ValueError(f"kept index {k} is outside the outline of {n} points")
        out.add(k % n)
    return out


def point_segment_distance(q, a, b):
    """Distance of points q (m,2) to the segment a-b."""
    q = np.atleast_2d(q)
    d = b - a
    dd = float(d @ d)
    if dd == 0.0:
        return np.linalg.norm(q - a, axis=1)
    s = np.clip(((q - a) @ d) / dd, 0.0, 1.0)
    return np.linalg.norm(q - (a + s[:, None] * d), axis=1)


def distance_to_polyline(q, ring):
    """Distance of points q (m,2) to the closed polyline `ring` (k,2)."""
    q = np.atleast_2d(np.asarray(q, dtype=float))
    ring = np.asarray(ring, dtype=float)
    a = ring
    b = np.roll(ring, -1, axis=0)
    d = b - a
    dd = np.einsum("ij,ij->i", d, d)
    dd[dd == 0.0] = 1.0
    # (m, k): parameter of q's foot on every segment
    s = np.clip(((q[:, None, :] - a[None]) * d[None]).sum(axis=2) / dd[None], 0.0, 1.0)
    foot = a[None] + s[..., None] * d[None]
    return np.linalg.norm(q[:, None, :] - foot, axis=2).min(axis=1)


# ---------------------------------------------------------------- simplification

def _collapse_jogs(p, tol, keep):
    """Indices left after every run of points within tol of the run's first point is
    replaced by one of its points (a kept one, else the one farthest from the chord of
    the run's outer neighbours: the corner)."""
    n = len(p)
    step = np.linalg.norm(np.roll(p, -1, axis=0) - p, axis=1)  # i -> i+1
    if tol <= 0.0 or np.all(step > tol):
        return list(range(n))
    # start the scan at a point that is not close to its predecessor
    far = np.nonzero(np.roll(step, 1) > tol)[0]
    if len(far) == 0:
        return list(range(n))  # every point within tol of the next: nothing to collapse safely
    start = int(far[0])
    order = [(start + i) % n for i in range(n)]
    out = []
    i = 0
    while i < n:
        first = order[i]
        run = [first]
        j = i + 1
        while j < n and np.linalg.norm(p[order[j]] - p[first]) <= tol:
            run.append(order[j])
            j += 1
        if len(run) == 1:
            out.append(first)
        else:
            kept = [k for k in run if k in keep]
            if kept:
                out.extend(kept)
            else:
                before = p[order[i - 1]] if i > 0 else p[order[-1]]
                after = p[order[j]] if j < n else p[order[0]]
                dev = point_segment_distance(p[run], before, after)
                out.append(run[int(np.argmax(dev))])  # ties: the first
        i = j
    return sorted(out)


def simplify(points, tolerance=DEFAULT_SIMPLIFY_TOLERANCE, keep=()):
    """Indices (ascending) of the vertices of a closed outline left after removing
    sub-`tolerance` jogs and (near-)collinear points; every input point stays within
    `tolerance` of the simplified path (within 2x for the points of a jog run), kept
    indices and the outline's corners stay, and no point is moved. tolerance 0: none
    removed."""
    p = _as_points(points)
    tol = _check_tolerance("simplify tolerance (mm)", tolerance)
    n = len(p)
    keep = _keep_set(keep, n)
    if tol == 0.0:
        return np.arange(n)
    alive = _collapse_jogs(p, tol, keep)
    if len(alive) < 3:
        return np.arange(n)  # a sliver under the tolerance: left as it is
    if len(alive) == 3:
        return np.array(alive)
    m = len(alive)
    prev = {alive[k]: alive[k - 1] for k in range(m)}
    nxt = {alive[k]: alive[(k + 1) % m] for k in range(m)}

    def span(a, b):  # input indices strictly between a and b going forward
        if b > a:
            return np.arange(a + 1, b)
        return np.concatenate([np.arange(a + 1, n), np.arange(0, b)])

    def cost(i):
        a, b = prev[i], nxt[i]
        q = span(a, b)
        return float(point_segment_distance(p[q], p[a], p[b]).max())

    heap = [(cost(i), i) for i in alive if i not in keep]
    heapq.heapify(heap)
    current = {i: c for c, i in heap}
    count = m
    while heap and count > 3:
        c, i = heapq.heappop(heap)
        if current.get(i) != c:
            continue  # stale entry
        if c > tol:
            break
        a, b = prev[i], nxt[i]
        nxt[a], prev[b] = b, a
        del prev[i], nxt[i], current[i]
        count -= 1
        for j in (a, b):
            if j in current:
                current[j] = cost(j)
                heapq.heappush(heap, (current[j], j))
    return np.array(sorted(prev))


# ---------------------------------------------------------------- arc fitting

def turning_angles(points):
    """Turning angle (degrees, unsigned) of a closed polyline at each vertex."""
    p = np.asarray(points, dtype=float)
    d_in = p - np.roll(p, 1, axis=0)
    d_out = np.roll(p, -1, axis=0) - p
    cross = d_in[:, 0] * d_out[:, 1] - d_in[:, 1] * d_out[:, 0]
    dot = (d_in * d_out).sum(axis=1)
    return np.degrees(np.abs(np.arctan2(cross, dot)))


def _bulge_from_k(k, L):
    """Bulge of the circle x^2 + y^2 - L^2/4 = y/k through (+-L/2, 0), minor arc."""
    if k == 0.0:
        return 0.0
    ym = -k * L * L / (2.0 * (1.0 + math.sqrt(1.0 + k * k * L * L)))
    return -2.0 * ym / L


def _k_from_bulge(b, L):
    ym = -0.5 * b * L
    return ym / (ym * ym - 0.25 * L * L)


def _radial_deviation(x, y, k, L):
    """|distance to the circle| of local points (x, y), circle through (+-L/2, 0) with
    algebraic curvature k (stable as k -> 0: then the distance to the chord's line)."""
    a = x * x + y * y - 0.25 * L * L
    num = np.abs(k * a - y)
    den = np.hypot(k * x, k * y - 0.5) + math.sqrt(0.25 * k * k * L * L + 0.25)
    return num / den


def arc_deviation(run, bulge):
    """Largest distance between the polyline `run` (m,2) and the arc from run[0] to
    run[-1] with that bulge, or inf if the run does not advance monotonically along the
    arc. Checked: every vertex against the circle, every segment's inward bend."""
    run = np.asarray(run, dtype=float)
    p0, p1 = run[0], run[-1]
    c = p1 - p0
    L = float(np.hypot(*c))
    if L == 0.0:
        return math.inf
    ex = c / L
    ey = np.array([-ex[1], ex[0]])
    rel = run - 0.5 * (p0 + p1)
    x, y = rel @ ex, rel @ ey
    eps = 1e-9 * L
    if np.any(np.diff(x) <= -eps) or x.min() < -0.5 * L - eps or x.max() > 0.5 * L + eps:
        return math.inf
    k = _k_from_bulge(bulge, L)
    dev = float(_radial_deviation(x, y, k, L).max())
    if k != 0.0 and bulge != 0.0:
        # inward bend of each segment: its point nearest the centre (0, t), t = 1/(2k)
        t = 0.5 / k
        xa, ya, xb, yb = x[:-1], y[:-1], x[1:], y[1:]
        dx, dy = xb - xa, yb - ya
        dd = dx * dx + dy * dy
        ok = dd > 0
        s = np.zeros_like(dx)
        s[ok] = np.clip((-xa[ok] * dx[ok] + (t - ya[ok]) * dy[ok]) / dd[ok], 0.0, 1.0)
        fx, fy = xa + s * dx, ya + s * dy
        dev = max(dev, float(_radial_deviation(fx, fy, k, L).max()))
    return dev


def fit_bulge(run, max_bulge=1.0):
    """Least-squares bulge of the arc from run[0] to run[-1] through the points between
    (algebraic fit; |bulge| <= max_bulge)."""
    run = np.asarray(run, dtype=float)
    p0, p1 = run[0], run[-1]
    c = p1 - p0
    L = float(np.hypot(*c))
    if L == 0.0 or len(run) < 3:
        return 0.0
    ex = c / L
    ey = np.array([-ex[1], ex[0]])
    rel = run[1:-1] - 0.5 * (p0 + p1)
    x, y = rel @ ex, rel @ ey
    a = x * x + y * y - 0.25 * L * L
    aa = float(a @ a)
    if aa == 0.0:
        return 0.0
    k = float(a @ y) / aa
    b = _bulge_from_k(k, L)
    return float(np.clip(b, -max_bulge, max_bulge))


def _fits(p, idx, tol, max_bulge, ratio):
    """Bulge of an arc through the vertices p[idx] within tol, or None."""
    run = p[idx]
    seg = np.linalg.norm(np.diff(run, axis=0), axis=1)
    if seg.max() > ratio * float(np.median(seg)):
        return None
    b = fit_bulge(run, max_bulge)
    if b == 0.0:
        return None
    return b if arc_deviation(run, b) <= tol else None


def fit_arcs(points, chord_tolerance=DEFAULT_CHORD_TOLERANCE, keep=(),
             corner_angle=DEFAULT_CORNER_ANGLE, min_arc_segments=DEFAULT_MIN_ARC_SEGMENTS,
             length_ratio=DEFAULT_LENGTH_RATIO, max_sweep=180.0):
    """Arcs on a closed polyline: returns (indices of the vertices kept, bulge per kept
    vertex for the segment to the next kept vertex). Breakpoints (arcs end there): the
    `keep` indices and the corners (turning > corner_angle degrees). Deterministic."""
    p = _as_points(points)
    tol = _check_tolerance("chord tolerance (mm)", chord_tolerance)
    n = len(p)
    keep = _keep_set(keep, n)
    if tol == 0.0 or n < 4:
        return np.arange(n), np.zeros(n)
    max_bulge = math.tan(math.radians(min(max(max_sweep, 1e-6), 180.0)) / 4.0)
    breaks = sorted(keep | set(np.nonzero(turning_angles(p) > corner_angle)[0].tolist()))
    if not breaks:
        breaks = [0]
    # unrolled ring starting at the first breakpoint
    s0 = breaks[0]
    order = np.array([(s0 + i) % n for i in range(n + 1)])
    q = p[order]
    stops = sorted({(b - s0) % n for b in breaks} | {n})
    out_idx, out_b = [], []
    for s, e in zip(stops[:-1], stops[1:]):
        i = s
        while i < e:
            j = i + min_arc_segments
            best = None
            if j <= e:
                best_b = _fits(q, np.arange(i, j + 1), tol, max_bulge, length_ratio)
                if best_b is not None:
                    best = (j, best_b)
                    # gallop, then bisect between the last fit and the first failure
                    step, fail = 1, None
                    while best[0] < e:
                        j = min(best[0] + step, e)
                        b = _fits(q, np.arange(i, j + 1), tol, max_bulge, length_ratio)
                        if b is None:
                            fail = j
                            break
                        best = (j, b)
                        step *= 2
                    while fail is not None and fail - best[0] > 1:
                        j = (best[0] + fail) // 2
                        b = _fits(q, np.arange(i, j + 1), tol, max_bulge, length_ratio)
                        if b is None:
                            fail = j
                        else:
                            best = (j, b)
            out_idx.append(int(order[i]))
            if best is None:
                out_b.append(0.0)
                i += 1
            else:
                out_b.append(best[1])
                i = best[0]
    return np.array(out_idx), np.array(out_b, dtype=float)


def make_cut_path(outline, simplify_tolerance=DEFAULT_SIMPLIFY_TOLERANCE,
                  chord_tolerance=DEFAULT_CHORD_TOLERANCE, arcs=True, keep=(),
                  corner_angle=DEFAULT_CORNER_ANGLE):
    """The CAM path of a closed outline: simplified, then (arcs=True) fitted with arcs.
    `keep`: input indices that stay vertices (e.g. panel corners, fold ends)."""
    p = _as_points(outline)
    kept = simplify(p, simplify_tolerance, keep)
    q = p[kept]
    keep_set = _keep_set(keep, len(p))
    sub_keep = [k for k, i in enumerate(kept) if int(i) in keep_set]
    if arcs and len(q) >= 4:
        idx, bulges = fit_arcs(q, chord_tolerance, sub_keep, corner_angle)
    else:
        idx, bulges = np.arange(len(q)), np.zeros(len(q))
    # start the path at the earliest input index (stable order)
    src = kept[idx]
    r = int(np.argmin(src))
    return CutPath(np.roll(q[idx], -r, axis=0), np.roll(bulges, -r), np.roll(src, -r))


def arc_samples(p0, p1, bulge, max_step=1.0):
    """Points on the arc (or line for bulge 0) from p0 to p1, p0 included, p1 excluded."""
    p0, p1 = np.asarray(p0, dtype=float), np.asarray(p1, dtype=float)
    c = p1 - p0
    L = float(np.hypot(*c))
    if bulge == 0.0 or L == 0.0:
        m = max(1, int(math.ceil(L / max_step)))
        s = np.arange(m) / m
        return p0 + s[:, None] * c
    sweep = 4.0 * math.atan(bulge)  # signed, + = counter-clockwise
    r = L / (2.0 * math.sin(abs(sweep) / 2.0))
    ex = c / L
    ey = np.array([-ex[1], ex[0]])
    # centre: left of the chord for a counter-clockwise minor arc
    h = r * math.cos(abs(sweep) / 2.0)
    centre = 0.5 * (p0 + p1) + (h if sweep > 0 else -h) * ey
    a0 = math.atan2(p0[1] - centre[1], p0[0] - centre[0])
    m = max(2, int(math.ceil(abs(sweep) * r / max_step)))
    ang = a0 + sweep * np.arange(m) / m
    return centre + r * np.stack([np.cos(ang), np.sin(ang)], axis=1)


def sample_path(points, bulges, max_step=1.0):
    pts = np.asarray(points, dtype=float)
    parts = [arc_samples(pts[k], pts[(k + 1) % len(pts)], float(bulges[k]), max_step)
             for k in range(len(pts))]
    return np.vstack(parts)
