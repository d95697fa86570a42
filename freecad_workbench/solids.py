"""Solids for the workshop model: rods with a profile and simple hubs (needs FreeCAD).

    shape = tessella.rod_solids(r, profile=("rect", 60.0, 160.0))   # or ("pipe", R, t), ("circ", R)
    hubs = tessella.hub_solids(r, radius=80.0, height=200.0)

Rods run node to node; a rectangular profile's height is oriented along the mean
of the two node normals (projected square to the rod), its width across.
Hubs are cylinders centred on the nodes along the node axis. Compounds in rod /
node order.
"""

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


def rod_solids(result, profile=("rect", 60.0, 160.0)):
    import FreeCAD
    import Part

    kind, dims = _profile(profile)
    xyz = np.asarray(result.vertices, dtype=float)
    nrm = np.asarray(result.normals, dtype=float)
    solids = []
    for a, b in np.asarray(result.rods).reshape(-1, 2):
        p, q = xyz[a], xyz[b]
        t = q - p
        length = float(np.linalg.norm(t))
        t = t / length
        up = nrm[a] + nrm[b]
        up = up - np.dot(up, t) * t
        if np.linalg.norm(up) < 1e-12:
            up = np.cross(t, [1.0, 0, 0]) if abs(t[0]) < 0.9 else np.cross(t, [0, 1.0, 0])
        up = up / np.linalg.norm(up)
        side = np.cross(up, t)
        if kind == "rect":
            w, h = dims
            base = p - 0.5 * w * side - 0.5 * h * up
            corners = [base, base + w * side, base + w * side + h * up, base + h * up]
            pts = [FreeCAD.Vector(*map(float, c)) for c in corners]
            face = Part.Face(Part.makePolygon(pts + [pts[0]]))
            solids.append(face.extrude(FreeCAD.Vector(*map(float, t * length))))
        else:
            d = FreeCAD.Vector(*map(float, t))
            s = Part.makeCylinder(dims[0], length, FreeCAD.Vector(*map(float, p)), d)
            if kind == "pipe":
                s = s.cut(Part.makeCylinder(dims[0] - dims[1], length, FreeCAD.Vector(*map(float, p)), d))
            solids.append(s)
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
