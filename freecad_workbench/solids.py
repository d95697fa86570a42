"""Solids for the workshop model: rods with a profile and simple hubs (needs FreeCAD).

    shape = tessella.rod_solids(r, profile=("rect", 60.0, 160.0))   # or ("pipe", R, t), ("circ", R)
    hubs = tessella.hub_solids(r, radius=80.0, height=200.0)

Rods run node to node; a rectangular profile's height is oriented along the mean
of the two node normals (projected square to the rod), its width across.
Rod ends are mitred to the node planes of the cut list (ends="square" for
square cuts); rod_end_planes gives those planes.
Hubs are cylinders centred on the nodes along the node axis. Compounds in rod /
node order.
"""

import math

import numpy as np


def _profile(profile):
    kind = profile[0]
    dims = [float(v) for v in profile[1:]]
    need = {"rect": 2, "pipe": 2, "circ": 1}.get(kind)
    if need is None:
        raise ValueError(f"profile must start with 'rect', 'pipe' or 'circ', got {kind!r}")
    if len(dims) != need or any(not v > 0 for v in dims):
        raise ValueError(f"profile {kind!r} needs {need} positive dimension(s) (mm), got {dims}")
    if kind == "pipe" and dims[1] >= dims[0]:
        raise ValueError("pipe thickness must be less than its radius")
    return kind, dims


MAX_MITRE = 75.0  # deg: default largest tilt of a rod end from a square cut


def _unit3(v):
    return v / np.linalg.norm(v)


def _end_normal(t_in, z, up, max_mitre):
    """Unit normal of a rod's end plane, pointing into the rod (n . t_in > 0).

    t_in: unit rod direction from the node into the rod; z: unit node axis.
    The node plane contains z and t_in x z, so its normal is t_in projected
    square to z; it makes 90 deg - angle(t_in, z) = |cut angle| with the rod.
    Beyond max_mitre (rod nearly along the node axis) the plane is turned about
    the same line t_in x z to max_mitre; a rod exactly along the axis tilts
    towards `up` (the profile's height direction)."""
    n = t_in - np.dot(t_in, z) * z
    s = float(np.linalg.norm(n))  # = cos(tilt)
    if s >= math.cos(math.radians(max_mitre)):
        return n / s, False
    w = z - np.dot(z, t_in) * t_in
    if np.linalg.norm(w) < 1e-12:
        w = up
    else:
        w = -math.copysign(1.0, float(np.dot(t_in, z))) * w
    w = _unit3(w - np.dot(w, t_in) * t_in)
    m = math.radians(max_mitre)
    return math.cos(m) * t_in + math.sin(m) * w, True


def _rod_frame(p, q, na, nb):
    t = q - p
    length = float(np.linalg.norm(t))
    if not length > 0:
        raise ValueError("a rod has zero length")
    t = t / length
    up = na + nb
    up = up - np.dot(up, t) * t
    if np.linalg.norm(up) < 1e-12:
        up = np.cross(t, [1.0, 0, 0]) if abs(t[0]) < 0.9 else np.cross(t, [0, 1.0, 0])
    up = up / np.linalg.norm(up)
    side = np.cross(up, t)
    return t, length, up, side


def _vec(v):
    import FreeCAD

    return FreeCAD.Vector(*map(float, v))


def _prism(p, t, offsets, na, q, nb):
    """Planar-faced solid: the lines p + o + s t (o in offsets, a convex polygon
    square to t, counter-clockwise about t) cut by the plane through p with
    normal na and the plane through q with normal nb."""
    import Part

    lo = [p + o - (np.dot(na, o) / np.dot(na, t)) * t for o in offsets]
    hi = [q + o - (np.dot(nb, o) / np.dot(nb, t)) * t for o in offsets]
    k = len(offsets)

    def face(pts):
        v = [_vec(x) for x in pts]
        return Part.Face(Part.makePolygon(v + [v[0]]))

    faces = [face(lo[::-1]), face(hi)]
    for i in range(k):
        j = (i + 1) % k
        faces.append(face([lo[i], lo[j], hi[j], hi[i]]))
    solid = Part.Solid(Part.Shell(faces))
    if solid.Volume < 0:
        solid.reverse()
    return solid


def _outside(point, n_in, size):
    """A box of edge 2*size x 2*size x size on the outer side of the plane
    through point with inward normal n_in (a half-space for a rod end)."""
    import FreeCAD
    import Part

    box = Part.makeBox(2 * size, 2 * size, size, FreeCAD.Vector(-size, -size, 0))
    rot = FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), _vec(-n_in))
    box.Placement = FreeCAD.Placement(_vec(point), rot)
    return box


def rod_end_planes(result, ends="mitred", max_mitre=MAX_MITRE):
    """Per rod (rod order) the two end planes the solids are cut with: dict of
    arrays point_a/b (the nodes), normal_a/b (unit, pointing into the rod),
    tilt_a/b (deg from a square cut) and clamped_a/b (True where the node plane
    would tilt more than max_mitre and the end is turned to max_mitre)."""
    if ends not in ("mitred", "square"):
        raise ValueError(f"ends must be 'mitred' or 'square', got {ends!r}")
    try:
        max_mitre = float(max_mitre)
    except (TypeError, ValueError):
        raise ValueError(f"max_mitre (deg) must be a number, got {max_mitre!r}") from None
    if not 0.0 < max_mitre < 90.0:
        raise ValueError(f"max_mitre (deg) must be in (0, 90), got {max_mitre!r}")
    xyz = np.asarray(result.vertices, dtype=float)
    nrm = np.asarray(result.normals, dtype=float)
    rods = np.asarray(result.rods, dtype=np.int64).reshape(-1, 2)
    out = {k: [] for k in ("point_a", "point_b", "normal_a", "normal_b",
                           "tilt_a", "tilt_b", "clamped_a", "clamped_b")}
    for a, b in rods:
        p, q = xyz[a], xyz[b]
        t, _, up, _ = _rod_frame(p, q, nrm[a], nrm[b])
        if ends == "square":
            (na, ca), (nb, cb) = (t, False), (-t, False)
        else:
            na, ca = _end_normal(t, _unit3(nrm[a]), up, max_mitre)
            nb, cb = _end_normal(-t, _unit3(nrm[b]), up, max_mitre)
        for s, pt, n, c, tin in (("a", p, na, ca, t), ("b", q, nb, cb, -t)):
            out["point_" + s].append(pt)
            out["normal_" + s].append(n)
            out["tilt_" + s].append(math.degrees(math.acos(min(1.0, float(np.dot(n, tin))))))
            out["clamped_" + s].append(c)
    res = {}
    for key, v in out.items():
        if key.startswith("clamped"):
            res[key] = np.asarray(v, dtype=bool)
        else:
            res[key] = np.asarray(v, dtype=float).reshape((len(rods), 3) if key[0] in "pn" else (len(rods),))
    return res


def rod_solids(result, profile=("rect", 60.0, 160.0), ends="mitred", max_mitre=MAX_MITRE):
    """One solid per rod (compound in rod order), node to node along the rod.

    profile: ("rect", width, height), ("pipe", R, thickness) or ("circ", R), mm.
    A rectangle's height follows the mean of the two node normals (squared to
    the rod), its width runs across.

    ends="mitred" (default): each end is cut by the node plane of rod_data /
    cut_list - the plane through the node that contains the node axis and the
    line square to both rod and axis (rod x axis). Its normal is the rod
    direction projected square to the node axis, so it makes exactly the cut
    angle |cut_angle_a/b| = |90 - axis_angle| with the rod: the end sits flat
    against a hub along the node axis. Both planes pass through the ends of the
    rod's centre line, so the volume is profile area x node-to-node length.
    Where the node plane would tilt more than max_mitre (deg, default 75; a
    rod within 15 deg of its node axis) the end is turned about the same line
    to max_mitre instead of running to an unbounded point (rod_end_planes tells
    which). ends="square": cut square to the rod at the nodes.

    Raises ValueError when the two end cuts of a rod would cross inside its
    profile (a rod too short for its profile and cut angles)."""
    import FreeCAD  # noqa: F401  (before Part)
    import Part

    kind, dims = _profile(profile)
    planes = rod_end_planes(result, ends, max_mitre)
    xyz = np.asarray(result.vertices, dtype=float)
    nrm = np.asarray(result.normals, dtype=float)
    rods = np.asarray(result.rods, dtype=np.int64).reshape(-1, 2)
    ids = list(getattr(result, "rod_ids", range(len(rods))))
    solids = []
    for k, (a, b) in enumerate(rods):
        p, q = xyz[a], xyz[b]
        t, length, up, side = _rod_frame(p, q, nrm[a], nrm[b])
        na, nb = planes["normal_a"][k], planes["normal_b"][k]
        # centre-line length between the cuts at profile offset o: length + o . g
        g = na / np.dot(na, t) - nb / np.dot(nb, t)
        g = g - np.dot(g, t) * t
        if kind == "rect":
            w, h = dims
            offsets = [-0.5 * w * side - 0.5 * h * up, 0.5 * w * side - 0.5 * h * up,
                       0.5 * w * side + 0.5 * h * up, -0.5 * w * side + 0.5 * h * up]
            shortest = length + min(float(np.dot(o, g)) for o in offsets)
        else:
            shortest = length - dims[0] * float(np.linalg.norm(g))
        if not shortest > 1e-6 * max(length, 1.0):
            raise ValueError(
                f"rod {ids[k]}: its end cuts cross inside the {kind} profile {dims} "
                f"(length {length:.3f} mm); use a smaller profile or ends='square'")
        if kind == "rect":
            solids.append(_prism(p, t, offsets, na, q, nb))
            continue
        r_out = dims[0]
        if ends == "square":
            s = Part.makeCylinder(r_out, length, _vec(p), _vec(t))
            if kind == "pipe":
                s = s.cut(Part.makeCylinder(r_out - dims[1], length, _vec(p), _vec(t)))
            solids.append(s)
            continue
        # long cylinder past both cuts, then the outer sides of the end planes cut off
        reach = r_out * max(float(np.linalg.norm(na - np.dot(na, t) * t) / np.dot(na, t)),
                            float(np.linalg.norm(nb - np.dot(nb, t) * t) / -np.dot(nb, t)))
        m = reach + 0.1 * r_out + 1.0
        start, span = p - m * t, length + 2 * m
        s = Part.makeCylinder(r_out, span, _vec(start), _vec(t))
        if kind == "pipe":
            s = s.cut(Part.makeCylinder(r_out - dims[1], span, _vec(start), _vec(t)))
        size = 2.0 * (r_out + m) + 10.0
        s = s.cut(_outside(p, na, size)).cut(_outside(q, nb, size))
        solid = s.Solids
        if len(solid) != 1:
            raise ValueError(f"rod {ids[k]}: mitred {kind} solid has {len(solid)} pieces")
        solids.append(solid[0])
    return Part.makeCompound(solids)


def hub_solids(result, radius=80.0, height=200.0):
    import FreeCAD
    import Part

    if not (radius > 0 and height > 0):
        raise ValueError("radius and height (mm) must be > 0")
    nodes = np.asarray(result.nodes, dtype=np.int64)  # one hub per node (rod end)
    xyz = np.asarray(result.vertices, dtype=float)[nodes]
    nrm = np.asarray(result.normals, dtype=float)[nodes]
    hubs = []
    for p, n in zip(xyz, nrm):
        n = n / np.linalg.norm(n)
        base = p - 0.5 * height * n
        hubs.append(Part.makeCylinder(float(radius), float(height),
                                      FreeCAD.Vector(*map(float, base)), FreeCAD.Vector(*map(float, n))))
    return Part.makeCompound(hubs)


def panel_solids(result, thickness=8.0, side="back", flat=None):
    """Panels as solids of the given thickness: each panel's triangles (as unfolded:
    the fold diagonal of a bent quad, the (u,v) triangulation of an n-gon) offset
    along the node normals. side: "back" (against the normal, the front face stays
    on the surface), "front" (along it) or "center". Compound in panel order."""
    import FreeCAD
    import Part

    from .fabrication import unfold

    if not thickness > 0:
        raise ValueError(f"thickness (mm) must be > 0, got {thickness!r}")
    shift = {"back": (-1.0, 0.0), "front": (0.0, 1.0), "center": (-0.5, 0.5)}.get(side)
    if shift is None:
        raise ValueError(f"side must be 'back', 'front' or 'center', got {side!r}")
    flat = flat if flat is not None else unfold(result)
    xyz = np.asarray(result.vertices, dtype=float)
    nrm = np.asarray(result.normals, dtype=float)
    nrm = nrm / np.linalg.norm(nrm, axis=1)[:, None]
    solids = []
    for panel, f in zip(result.panels, flat):
        idx = list(panel)
        lo = xyz[idx] + shift[0] * thickness * nrm[idx]
        hi = xyz[idx] + shift[1] * thickness * nrm[idx]
        k = len(idx)
        tris = []
        for a, b, c in f.triangles:
            tris.append((hi[a], hi[b], hi[c]))
            tris.append((lo[a], lo[c], lo[b]))
        for i in range(k):
            j = (i + 1) % k
            tris.append((lo[i], lo[j], hi[j]))
            tris.append((lo[i], hi[j], hi[i]))
        # exact double coordinates (a Mesh would round them to float32)
        faces = []
        for t in tris:
            pts = [FreeCAD.Vector(*map(float, q)) for q in t]
            faces.append(Part.Face(Part.makePolygon(pts + [pts[0]])))
        shell = Part.Shell(faces)
        shell.sewShape()
        solid = Part.Solid(Part.Shell(shell.Faces))
        if solid.Volume < 0:
            solid.reverse()
        solids.append(solid)
    return Part.makeCompound(solids)
