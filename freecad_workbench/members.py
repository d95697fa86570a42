"""Rods and nodes for fabrication, and the buildability summary.

    rods = tessella.rod_data(r)        # dict of arrays, rod order (IDs r.rod_ids)
    nodes = tessella.node_frames(r)    # list per node: axis, incident rods and their angles
    types = tessella.node_types(r, angle_tol=0.5)
    cuts = tessella.cut_list(r, length_tol=1.0, angle_tol=0.5)
    s = tessella.buildability(r, flat=flat, layout=layout)

Node axis = the surface normal at the node. Angles in degrees, lengths in mm.
No FreeCAD import.
"""

import math

import numpy as np


def _unit(v):
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    return v / np.where(n == 0, 1.0, n)


def _deg(x):
    return np.degrees(x)


def rod_data(result):
    """Per rod: node_a, node_b, length, direction (unit, a->b), axis_angle_a/b
    (between the rod and the node axis at that end; 90 = square to the axis),
    cut_angle_a/b = 90 - axis angle (the end cut's tilt from a square cut, in the
    plane of rod and node axis) and twist (rotation of the node axes about the rod
    between its ends, signed)."""
    xyz = np.asarray(result.vertices, dtype=float)
    nrm = _unit(np.asarray(result.normals, dtype=float))
    rods = np.asarray(result.rods, dtype=np.int64).reshape(-1, 2)
    a, b = rods[:, 0], rods[:, 1]
    d = xyz[b] - xyz[a]
    length = np.linalg.norm(d, axis=1)
    t = _unit(d)
    ang_a = _deg(np.arccos(np.clip(np.sum(t * nrm[a], axis=1), -1, 1)))
    # at end b the rod points back to a
    ang_b = _deg(np.arccos(np.clip(np.sum(-t * nrm[b], axis=1), -1, 1)))
    # twist: node axes projected perpendicular to the rod, signed about t
    pa = _unit(nrm[a] - np.sum(nrm[a] * t, axis=1)[:, None] * t)
    pb = _unit(nrm[b] - np.sum(nrm[b] * t, axis=1)[:, None] * t)
    twist = _deg(np.arctan2(np.sum(np.cross(pa, pb) * t, axis=1), np.sum(pa * pb, axis=1)))
    return {
        "id": list(result.rod_ids),
        "node_a": a,
        "node_b": b,
        "length": length,
        "direction": t,
        "axis_angle_a": ang_a,
        "axis_angle_b": ang_b,
        "cut_angle_a": 90.0 - ang_a,
        "cut_angle_b": 90.0 - ang_b,
        "twist": twist,
    }


def _greedy_groups(keys, close, tol0):
    """Deterministic clustering: items in key order join the first group whose
    representative is close, else start a group. keys[i][0] must differ by at
    most tol0 within a group (used to look only at nearby representatives).
    Returns (group index per item, representative item per group)."""
    import bisect

    order = sorted(range(len(keys)), key=lambda i: keys[i])
    reps, rep_first, group = [], [], [0] * len(keys)
    for i in order:
        lo = bisect.bisect_left(rep_first, keys[i][0] - tol0)
        for g in range(lo, len(reps)):
            if rep_first[g] > keys[i][0] + tol0:
                break
            if close(keys[reps[g]], keys[i]):
                group[i] = g
                break
        else:
            group[i] = len(reps)
            reps.append(i)
            rep_first.append(keys[i][0])  # increasing: items come in key order
    return group, reps


def cut_list(result, length_tol=1.0, angle_tol=0.5):
    """Rods grouped into types: equal length within length_tol (mm) and equal end
    cut angles within angle_tol (deg; a rod may be turned end for end).
    Returns a list of dicts (type, count, length, cut_angle_1, cut_angle_2, rods)
    sorted by length."""
    if not (length_tol >= 0 and angle_tol >= 0):
        raise ValueError("length_tol and angle_tol must be >= 0")
    rd = rod_data(result)
    keys = []
    for k in range(len(rd["id"])):
        c1, c2 = sorted((float(rd["cut_angle_a"][k]), float(rd["cut_angle_b"][k])))
        keys.append((float(rd["length"][k]), c1, c2))

    def close(p, q):
        return (abs(p[0] - q[0]) <= length_tol and abs(p[1] - q[1]) <= angle_tol
                and abs(p[2] - q[2]) <= angle_tol)

    group, reps = _greedy_groups(keys, close, length_tol)
    out = []
    for g, rep in enumerate(reps):
        members = [i for i in range(len(keys)) if group[i] == g]
        out.append({
            "type": f"RT-{g + 1:03d}",
            "count": len(members),
            "length": keys[rep][0],
            "cut_angle_1": keys[rep][1],
            "cut_angle_2": keys[rep][2],
            "max_length_diff": max(abs(keys[i][0] - keys[rep][0]) for i in members),
            "rods": [rd["id"][i] for i in members],
        })
    return out


def node_frames(result):
    """Per node: id, point, axis (unit normal), frame x/y (x = the first incident
    rod projected on the tangent plane), and the incident rods sorted
    counter-clockwise about the axis with azimuth (deg, [0, 360)) and elevation
    (deg above the tangent plane)."""
    xyz = np.asarray(result.vertices, dtype=float)
    nrm = _unit(np.asarray(result.normals, dtype=float))
    rods = np.asarray(result.rods, dtype=np.int64).reshape(-1, 2)
    incident = [[] for _ in range(len(xyz))]
    for k, (a, b) in enumerate(rods):
        incident[a].append((k, b))
        incident[b].append((k, a))
    rod_ids, node_ids = result.rod_ids, result.node_ids
    out = []
    for node, n in enumerate(np.asarray(result.nodes, dtype=np.int64)):
        z = nrm[n]
        entries = []
        x = None
        for k, other in sorted(incident[n]):
            d = _unit(xyz[other] - xyz[n])
            tang = d - np.dot(d, z) * z
            if x is None and np.linalg.norm(tang) > 1e-12:
                x = _unit(tang)
            entries.append((k, d))
        if x is None:
            x = _unit(np.cross(z, [1.0, 0, 0]) if abs(z[0]) < 0.9 else np.cross(z, [0, 1.0, 0]))
        y = np.cross(z, x)
        rods_here = []
        for k, d in entries:
            az = math.degrees(math.atan2(float(np.dot(d, y)), float(np.dot(d, x)))) % 360.0
            el = math.degrees(math.asin(float(np.clip(np.dot(d, z), -1, 1))))
            rods_here.append({"rod": rod_ids[k], "azimuth": az, "elevation": el})
        rods_here.sort(key=lambda e: e["azimuth"])
        out.append({"id": node_ids[node], "point": xyz[n], "axis": z, "x": x, "y": y,
                    "rods": rods_here})
    return out


def _node_signature(frame):
    """Cyclic sequence of (azimuth gap to the next rod, elevation): independent
    of the frame's x axis, so equal up to a rotation about the node axis."""
    rods = frame["rods"]
    k = len(rods)
    sig = []
    for i in range(k):
        gap = (rods[(i + 1) % k]["azimuth"] - rods[i]["azimuth"]) % 360.0 if k > 1 else 360.0
        sig.append((gap, rods[i]["elevation"]))
    return sig


def _same_cyclic(s, t, tol):
    if len(s) != len(t):
        return False
    k = len(s)
    for shift in range(k):
        if all(abs(s[i][0] - t[(i + shift) % k][0]) <= tol
               and abs(s[i][1] - t[(i + shift) % k][1]) <= tol for i in range(k)):
            return True
    return k == 0


def node_types(result, angle_tol=0.5, frames=None):
    """Nodes equal within angle_tol (deg) count as one type; rotations about the
    node axis are allowed (a hub can be turned), mirror images are not.
    Returns (type index per node, list of types {type, count, valence, nodes})."""
    if not angle_tol >= 0:
        raise ValueError("angle_tol must be >= 0")
    frames = frames if frames is not None else node_frames(result)
    import bisect

    sigs = [_node_signature(f) for f in frames]
    # Candidates share the valence and the smallest azimuth gap within angle_tol
    # (a necessary condition), looked up by bisection.
    buckets = {}  # valence -> (sorted smallest gaps, type indices)
    reps, types = [], []
    for n, sig in enumerate(sigs):
        g0 = min((g for g, _ in sig), default=0.0)
        firsts, idx = buckets.setdefault(len(sig), ([], []))
        lo = bisect.bisect_left(firsts, g0 - angle_tol)
        hi = bisect.bisect_right(firsts, g0 + angle_tol)
        found = -1
        for t in sorted(idx[lo:hi]):
            if _same_cyclic(sigs[reps[t]], sig, angle_tol):
                found = t
                break
        if found < 0:
            found = len(reps)
            reps.append(n)
            pos = bisect.bisect_right(firsts, g0)
            firsts.insert(pos, g0)
            idx.insert(pos, found)
        types.append(found)
    summary = []
    for t, rep in enumerate(reps):
        members = [frames[n]["id"] for n in range(len(sigs)) if types[n] == t]
        summary.append({"type": f"NT-{t + 1:03d}", "count": len(members),
                        "valence": len(sigs[rep]), "nodes": members})
    return types, summary


def panel_types(flat, length_tol=1.0, angle_tol=0.5):
    """Flat panels congruent within length_tol (mm) and angle_tol (deg, corner
    angles and fold angle) share a type; corner order may start anywhere (a panel
    can be turned), mirror images differ (front and back differ).

    Greedy in panel order: a panel joins the first type whose first panel it
    matches, else starts a new one (types numbered by first appearance). The
    grouping runs in the core (cpp_core/include/tessella/panel_types.h), in
    O(n log n). Returns (type index per panel, number of types)."""
    from . import core

    p = core.PanelTypeParams()
    p.length_tol = float(length_tol)
    p.angle_tol = float(angle_tol)
    t = core.panel_types([np.asarray(f.outline, dtype=float).reshape(-1, 2) for f in flat],
                         [float(f.fold_angle) for f in flat], p)
    return t.type.tolist(), int(t.count)


def freegrid_planarity(result):
    """freeGrid benchmark form: 1 + mean over panels of (mean distance of the
    corners to their best-fit plane / half the perimeter). 1 = all planar."""
    xyz = np.asarray(result.vertices, dtype=float)
    vals = []
    for panel in result.panels:
        p = xyz[list(panel)]
        c = p.mean(axis=0)
        normal = np.linalg.svd(p - c)[2][-1]
        dist = np.abs((p - c) @ normal).mean()
        half = 0.5 * np.linalg.norm(np.roll(p, -1, axis=0) - p, axis=1).sum()
        vals.append(dist / half)
    return 1.0 + float(np.mean(vals)) if vals else 1.0


def buildability(result, flat=None, layout=None, length_tol=1.0, angle_tol=0.5,
                 family_tolerance=None, mirror=True):
    """Summary for the whole panelization (dict). `flat` (from unfold) adds the
    panel types and fold figures, `layout` (from nest) the sheet figures,
    `family_tolerance` (mm) the panel families (freecad_workbench.families):
    panel_families, largest_family, panels_per_family, family_max_error."""
    rd = rod_data(result)
    lengths = rd["length"]
    _, ntypes = node_types(result, angle_tol)
    s = {
        "panel_count": len(result.panels),
        "planarity_freegrid": freegrid_planarity(result),
        "rod_count": len(lengths),
        "rod_types": len(cut_list(result, length_tol, angle_tol)),
        "rod_length_similarity": 1.0 + float(np.std(lengths) / np.mean(lengths)) if len(lengths) else 1.0,
        "total_rod_length": float(np.sum(lengths)),
        "node_count": len(result.nodes),
        "node_types": len(ntypes),
        "panel_area_3d": float(np.sum(result.metrics["panel_area"])),
    }
    if flat is not None:
        s["panel_types"] = panel_types(flat, length_tol, angle_tol)[1]
        s["flat_area"] = float(sum(f.area for f in flat))
        s["folded_panels"] = sum(1 for f in flat if f.folds)
        s["self_intersecting_outlines"] = sum(1 for f in flat if getattr(f, "self_intersecting", False))
        s["max_fold_angle"] = float(max((f.fold_angle for f in flat), default=0.0))
    if family_tolerance is not None:
        from .families import panel_families

        fs = panel_families(result, family_tolerance, mirror).summary()
        s["panel_families"] = fs["families"]
        s["largest_family"] = fs["largest_family"]
        s["panels_per_family"] = fs["mean_panels_per_family"]
        s["family_max_error"] = fs["max_error"]
    if layout is not None:
        s["sheets"] = layout.sheet_count
        s["sheet_area"] = float(sum(w * h for w, h in (
            layout.sheet_size(k) for k in range(layout.sheet_count))))
        s["sheet_sizes"] = [tuple(layout.sheet_size(k)) for k in range(layout.sheet_count)]
        s["nesting_utilization"] = layout.utilization
    return s
