"""Schedules as FreeCAD Spreadsheet objects (a snapshot, not parametric).

    sheets = tessella.make_schedules(panelization_obj)   # PanelSchedule, RodSchedule, NodeSchedule

With panel families on (the Panels object's FamilyTolerance > 0), the panel
schedule gets a Family column and a FamilySchedule sheet lists each family:
its template's panel ID, the panel count, the largest error and the members.

The same columns as the CSV files of freecad_workbench.export.members
(panel fabrication schedule, rod data, node schedule), in one transaction,
with readable headers (SHEET_COLUMNS), lengths, angles and areas as FreeCAD
quantities (areas displayed in m²; `sheet.get("F2").Value` is mm²),
planarity in percent and the node schedule's rods as "R-0001 (az°, el°)".
"""

import csv
import os
import tempfile


import re

#: How each CSV column shows in a sheet: (header, kind). Kinds: "text", "count",
#: "number", a unit the value carries ("mm", "deg", "mm^2" shown in m², read
#: back as FreeCAD quantities), "percent" (a ratio shown x 100) and "rods" (the
#: node schedule's "R-0001@az/el" list, shown as "R-0001 (az°, el°), ...").
SHEET_COLUMNS = {
    "id": ("ID", "text"), "type": ("Type", "text"), "vertex_count": ("Corners", "count"),
    "flat_width_mm": ("Flat width", "mm"), "flat_height_mm": ("Flat height", "mm"),
    "area_mm2": ("Area", "mm^2"), "flat_area_mm2": ("Flat area", "mm^2"),
    "perimeter_mm": ("Perimeter", "mm"), "deviation_mm": ("Deviation", "mm"),
    "planarity": ("Planarity (% of edge)", "percent"), "fold": ("Fold diagonal", "text"),
    "fold_angle_deg": ("Fold angle", "deg"), "fold_valley": ("Valley fold", "count"),
    "folds": ("Folds", "count"),
    "node_a": ("Node A", "text"), "node_b": ("Node B", "text"), "length_mm": ("Length", "mm"),
    "cut_angle_a_deg": ("Cut angle A", "deg"), "cut_angle_b_deg": ("Cut angle B", "deg"),
    "twist_deg": ("Twist", "deg"),
    "x": ("X", "mm"), "y": ("Y", "mm"), "z": ("Z", "mm"), "axis_x": ("Axis X", "number"),
    "axis_y": ("Axis Y", "number"), "axis_z": ("Axis Z", "number"),
    "valence": ("Rod count", "count"), "rods": ("Rods (azimuth, elevation)", "rods"),
    "family": ("Family", "text"), "template": ("Template", "text"), "count": ("Panels", "count"),
    "max_error_mm": ("Max error", "mm"), "members": ("Members", "text"),
    "warp_mm": ("Warp", "mm"), "class": ("Class", "text"),
}

#: Display unit per kind (areas of panels read in m², as quantity surveyors do).
_DISPLAY_UNIT = {"mm^2": "m^2"}

_ROD_ENTRY = re.compile(r"(.+?)@([-+0-9.eE]+|nan|inf)/([-+0-9.eE]+|nan|inf)(?:\s+|$)")


def _col(k):
    s = ""
    k += 1
    while k:
        k, r = divmod(k - 1, 26)
        s = chr(65 + r) + s
    return s


def readable_rods(cell):
    """'R-0001@12.25/-0.9 R-0002@...' -> 'R-0001 (12.3°, -0.9°), R-0002 (...)'."""
    return ", ".join(f"{rid} ({float(az):.1f}°, {float(el):.1f}°)"
                     for rid, az, el in _ROD_ENTRY.findall(cell))


def _content(kind, value):
    """The cell content for one CSV value of the given kind."""
    if kind in ("text", "rods"):
        return "'" + (readable_rods(value) if kind == "rods" else value)
    number = float(value)
    if kind == "count":
        return str(int(round(number)))
    if kind == "number":
        return repr(number)
    if kind == "percent":
        return f"={100.0 * number!r}"
    return f"={number!r} {kind}"


def _fill(sheet, rows):
    """Header row (bold, readable names) and one row per item; numbers with
    units are quantities, so the sheet shows them in the user's unit schema."""
    header = rows[0]
    titles = [SHEET_COLUMNS.get(name, (name, "text"))[0] for name in header]
    kinds = [SHEET_COLUMNS.get(name, (name, "text"))[1] for name in header]
    for j, title in enumerate(titles):
        sheet.set(f"{_col(j)}1", "'" + title)
    for i, row in enumerate(rows[1:], start=2):
        for j, value in enumerate(row):
            if value == "":
                continue
            try:
                sheet.set(f"{_col(j)}{i}", _content(kinds[j], value))
            except ValueError:  # not a number after all: keep what the CSV says
                sheet.set(f"{_col(j)}{i}", "'" + value)
    last = _col(len(header) - 1)
    sheet.setStyle(f"A1:{last}1", "bold")
    for j, kind in enumerate(kinds):
        if kind in _DISPLAY_UNIT and len(rows) > 1:
            sheet.setDisplayUnit(f"{_col(j)}2:{_col(j)}{len(rows)}", _DISPLAY_UNIT[kind])
        width = 360 if kind == "rods" or header[j] == "members" else max(90, 8 * len(titles[j]))
        sheet.setColumnWidth(_col(j), width)


def _panels_proxy_call(panelization, name):
    """What the Panelization's Panels object's Proxy method `name` returns for
    it, or None (no Panels child)."""
    from .features import panelization as pfeat

    for child in pfeat.children_of(panelization):
        if child.Role == "Panels" and hasattr(child.Proxy, name):
            return getattr(child.Proxy, name)(child)
    return None


def panel_families_of(panelization):
    """families.PanelFamilies of a Panelization's Panels object at its
    FamilyTolerance / Mirror, or None (families off, or no Panels child)."""
    return _panels_proxy_call(panelization, "families")


def panel_classes_of(panelization):
    """panel_classes.PanelClasses of a Panelization's Panels object at its
    FlatTolerance / ColdBendRatio / ColdBendWarp, or None (no Panels child)."""
    return _panels_proxy_call(panelization, "classes")


def make_schedules(panelization, doc=None, fold_tolerance=0.01):
    import FreeCAD  # noqa: F401

    from . import fabrication
    from .export import members as mx
    from .features import panelization as pfeat

    if not pfeat.is_panelization(panelization):
        raise ValueError("make_schedules needs a Panelization object")
    doc = doc or panelization.Document
    res = panelization.Proxy.result(panelization).result
    flat = fabrication.unfold(res, fold_tolerance=fold_tolerance)
    fam = panel_families_of(panelization)
    cls = panel_classes_of(panelization)
    writers = [("PanelSchedule", lambda p: mx.write_panel_fabrication_schedule(
                   res, flat, p, families=fam, classes=cls)),
               ("RodSchedule", lambda p: mx.write_rod_data(res, p)),
               ("NodeSchedule", lambda p: mx.write_node_schedule(res, p))]
    if fam is not None:
        from .export.schedule_csv import write_family_schedule

        writers.append(("FamilySchedule", lambda p: write_family_schedule(res, fam, p)))
    tables = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, write in writers:
            path = os.path.join(tmp, name + ".csv")
            write(path)
            with open(path, newline="", encoding="utf-8") as f:
                tables[name] = list(csv.reader(f))
    doc.openTransaction("Schedules")
    created = []
    try:
        for name, rows in tables.items():
            sheet = doc.addObject("Spreadsheet::Sheet", name)
            created.append(sheet.Name)
            sheet.Label = f"{panelization.Label} {name}"
            _fill(sheet, rows)
            sheet.recompute()
    except BaseException:
        doc.abortTransaction()
        for n in created:
            if doc.getObject(n) is not None:
                doc.removeObject(n)
        raise
    doc.commitTransaction()
    return [doc.getObject(n) for n in created]
