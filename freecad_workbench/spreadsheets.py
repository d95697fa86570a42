"""Schedules as FreeCAD Spreadsheet objects (a snapshot, not parametric).

    sheets = tessella.make_schedules(panelization_obj)   # PanelSchedule, RodSchedule, NodeSchedule

The same columns as the CSV files of freecad_workbench.export.members
(panel fabrication schedule, rod data, node schedule), in one transaction.
"""

import csv
import os
import tempfile


def _col(k):
    s = ""
    k += 1
    while k:
        k, r = divmod(k - 1, 26)
        s = chr(65 + r) + s
    return s


def _fill(sheet, rows):
    for i, row in enumerate(rows):
        for j, value in enumerate(row):
            if value == "":
                continue
            if i > 0:
                try:
                    float(value)
                    sheet.set(f"{_col(j)}{i + 1}", value)
                    continue
                except ValueError:
                    pass
            sheet.set(f"{_col(j)}{i + 1}", "'" + value)


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
    tables = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, write in (("PanelSchedule", lambda p: mx.write_panel_fabrication_schedule(res, flat, p)),
                            ("RodSchedule", lambda p: mx.write_rod_data(res, p)),
                            ("NodeSchedule", lambda p: mx.write_node_schedule(res, p))):
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
