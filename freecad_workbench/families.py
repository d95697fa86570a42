"""Panel families: panels that one template serves within a tolerance (console API).

    import freecad_workbench as tessella
    r = tessella.panelize(face, method="iso_grid", size=1500.0)
    fam = tessella.panel_families(r, family_tolerance=2.0, mirror=True)
    fam.labels        # family index of each panel (0-based, numbered by lowest panel)
    fam.templates     # panel index of each family's template
    fam.max_error     # per family: largest corner distance of a member to its template (mm)
    fam.error         # per panel: its corner distance to its family's template (mm)
    fam.counts        # panels per family
    fam.summary()     # {"families", "largest_family", "mean_panels_per_family", ...}

A panel belongs to a family when, after the best rigid alignment found onto the
family's template (Kabsch over every corner correspondence: the corner order
turned, and with `mirror` also reversed with a reflection allowed), no corner
is farther than `family_tolerance` (mm) from the template's. Kabsch minimises
the RMS distance, so the value is an upper bound of the least possible largest
distance: the tolerance holds conservatively. Grouping is a deterministic greedy
set cover (fewest families, approximately) in the core:
cpp_core/include/tessella/panel_families.h.
"""

from dataclasses import dataclass, field

import numpy as np

#: Default family tolerance (mm).
FAMILY_TOLERANCE = 2.0


def family_name(f):
    """The name of family f (0-based): PF-001, PF-002, ..."""
    return f"PF-{int(f) + 1:03d}"


def panel_corners(result):
    """One (k,3) array of 3D corners per panel of a result (panel order)."""
    xyz = np.asarray(result.vertices, dtype=float).reshape(-1, 3)
    return [xyz[list(p)] for p in result.panels]


@dataclass
class PanelFamilies:
    """Families of a result's panels (see the module docstring). Arrays are numpy."""

    labels: np.ndarray  # (P,) int: family of each panel
    templates: np.ndarray  # (F,) int: panel index of each family's template
    max_error: np.ndarray  # (F,) float mm
    error: np.ndarray  # (P,) float mm, against the panel's template
    tolerance: float = FAMILY_TOLERANCE
    mirror: bool = True
    #: panels this close to a lower-indexed one were grouped with it first:
    #: 1e-3 x tolerance, or tolerance / 32 ... / 4 in the coarse grouping (see the core's header)
    twin_radius: float = 0.0
    counts: np.ndarray = field(init=False)  # (F,) int: panels per family

    def __post_init__(self):
        self.counts = np.bincount(self.labels, minlength=len(self.templates)).astype(np.int64)

    @property
    def count(self):
        """Number of families."""
        return len(self.templates)

    def members(self, f):
        """Panel indices of family f (increasing)."""
        return np.flatnonzero(self.labels == f)

    def names(self):
        """Family name of each panel (PF-001, ...)."""
        return [family_name(f) for f in self.labels]

    def summary(self):
        """{'families', 'largest_family', 'mean_panels_per_family', 'max_error',
        'family_tolerance', 'mirror', 'coarse'} (coarse: the coarse grouping ran)."""
        n = len(self.labels)
        return {
            "families": self.count,
            "largest_family": int(self.counts.max()) if self.count else 0,
            "mean_panels_per_family": n / self.count if self.count else 0.0,
            "max_error": float(self.max_error.max()) if self.count else 0.0,
            "family_tolerance": float(self.tolerance),
            "mirror": bool(self.mirror),
            "coarse": bool(self.twin_radius > 0.01 * self.tolerance),
        }


def families_of_corners(corners, family_tolerance=FAMILY_TOLERANCE, mirror=True, max_pairs=0):
    """PanelFamilies of panels given as (k,3) corner arrays (k >= 3).

    max_pairs: candidate pairs measured before the coarse grouping takes over
    (0 = automatic, max(400000, 64 x panels); see the core's header).
    ValueError (from the core) for a tolerance that is not > 0 and finite, a
    panel with fewer than 3 corners or a non-finite coordinate."""
    from . import core

    try:
        tol = float(family_tolerance)
    except (TypeError, ValueError):
        raise ValueError(f"family_tolerance must be a number of mm, got {family_tolerance!r}") from None
    p = core.PanelFamilyParams()
    p.tolerance = tol
    p.mirror = bool(mirror)
    p.max_pairs = int(max_pairs)
    f = core.panel_families([np.asarray(c, dtype=float) for c in corners], p)
    return PanelFamilies(labels=f.labels.astype(np.int64), templates=f.templates.astype(np.int64),
                         max_error=np.asarray(f.max_error, dtype=float),
                         error=np.asarray(f.error, dtype=float), tolerance=tol, mirror=bool(mirror),
                         twin_radius=float(f.twin_radius))


def panel_families(result, family_tolerance=FAMILY_TOLERANCE, mirror=True, max_pairs=0):
    """PanelFamilies of a PanelizeResult's panels (their 3D corners)."""
    return families_of_corners(panel_corners(result), family_tolerance, mirror, max_pairs)


def family_rows(result, fam):
    """One dict per family: family, template (panel ID), count, max_error_mm,
    members (panel IDs), for the family schedule and the drawings."""
    ids = result.panel_ids
    rows = []
    for f, t in enumerate(fam.templates):
        rows.append({"family": family_name(f), "template": ids[int(t)],
                     "count": int(fam.counts[f]), "max_error_mm": float(fam.max_error[f]),
                     "members": [ids[int(k)] for k in fam.members(f)]})
    return rows


# ----------------------------------------------------------- drawings, nesting
def _flat_by_id(flat, result):
    by_id = {f.id: f for f in flat}
    missing = [pid for pid in result.panel_ids if pid not in by_id]
    if missing:
        raise ValueError(f"flat panel {missing[0]!r} is missing: unfold the result whose "
                         "families you draw (fabrication.unfold(result))")
    return by_id


def _check_families(result, fam):
    if fam is None or len(fam.labels) != len(result.panels):
        raise ValueError("the families are not of this result's panels: compute them with "
                         "tessella.panel_families(result, ...)")


def template_parts(flat, result, fam):
    """One flat part per family: its template's unfolded panel, with the family
    name (PF-001, ...) as ID (what a drawing labels and engraves)."""
    import dataclasses

    _check_families(result, fam)
    by_id = _flat_by_id(list(flat), result)
    ids = result.panel_ids
    return [dataclasses.replace(by_id[ids[int(t)]], id=family_name(f))
            for f, t in enumerate(fam.templates)]


def family_parts(flat, result, fam):
    """One flat part per panel (panel order): its family's template outline with
    the panel's own ID: every panel cut to its template (nesting by family: each
    template as many times as its family has panels)."""
    import dataclasses

    _check_families(result, fam)
    by_id = _flat_by_id(list(flat), result)
    ids = result.panel_ids
    return [dataclasses.replace(by_id[ids[int(fam.templates[f])]], id=ids[k])
            for k, f in enumerate(fam.labels)]


def members_lines(result, fam, per_line=12):
    """The list of members as text lines: a heading line per family
    ("PF-001: template P-0012, 24 panels, max error 0.412 mm") followed by its
    members' IDs, `per_line` to a line."""
    lines = []
    for row in family_rows(result, fam):
        lines.append(f"{row['family']}: template {row['template']}, {row['count']} panels, "
                     f"max error {row['max_error_mm']:.3f} mm")
        m = row["members"]
        for k in range(0, len(m), per_line):
            lines.append("    " + " ".join(m[k:k + per_line]))
    return lines
