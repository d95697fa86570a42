"""GUI test of what the 3D view shows (run like gui_test_panelize.py, see tests/gui/README).

Colour legends: one per coloured object, stacked in slots that never overlap,
clear of the navigation cube, each label readable on the background actually
rendered (contrast measured on a saved image), values in the unit the unit
schema picks; a hidden or deleted object takes its legend with it.

ID labels (view property ShowIds): one text per panel / rod / node, the IDs
of the schedules, at the item's place; they follow a recompute, hide with
the object and go with it. The Unfold lies beside the model, not over it.
"""

import os
import sys
import tempfile

import FreeCAD
import FreeCADGui as Gui

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_harness  # noqa: E402
from gui_harness import check, ensure_workbench, process_events  # noqa: E402


def bspline_face_with_hole():
    import Part

    surf = Part.BSplineSurface()
    poles = [[FreeCAD.Vector(i * 2500.0, j * 2500.0, 800.0 * ((i - 2) ** 2 - (j - 2) ** 2) / 4)
              for j in range(5)] for i in range(5)]
    surf.buildFromPolesMultsKnots(poles, [4, 1, 4], [4, 1, 4], [0, 0.4, 1], [0, 0.6, 1],
                                  False, False, 3, 3)
    hole = Part.makeCylinder(1500, 20000, FreeCAD.Vector(5000, 5000, -10000))
    faces = surf.toShape().cut(hole).Faces
    return faces[0]


def panelized_surface(doc, size=1500.0):
    """(Panelization, {role: child}) of an iso grid on the B-spline face with a hole."""
    import freecad_workbench as tessella
    from freecad_workbench.features.panelization import children_of

    src = doc.addObject("Part::Feature", "Surface")
    src.Shape = bspline_face_with_hole()
    parent = tessella.make_panelization((src, "Face1"), method="iso_grid", size=size)
    doc.recompute()
    return parent, {c.Role: c for c in children_of(parent)}


def rendered_pixel(image, x, y):
    """RGB of the saved image at normalized view coordinates (x, y)."""
    from PySide import QtGui

    w, h = image.width(), image.height()
    px = min(max(int(round((x + 1) / 2 * (w - 1))), 0), w - 1)
    py = min(max(int(round((1 - y) / 2 * (h - 1))), 0), h - 1)
    c = QtGui.QColor(image.pixel(px, py))
    return (c.red(), c.green(), c.blue())


def test_legends():
    from PySide import QtGui

    from freecad_workbench.gui import legend

    ensure_workbench()
    doc = FreeCAD.newDocument("TessellaLegends")
    schema = FreeCAD.Units.getSchema()
    try:
        parent, kids = panelized_surface(doc)
        pvp, rvp = kids["Panels"].ViewObject, kids["Rods"].ViewObject
        pvp.ColorBy = "Deviation"
        rvp.ColorBy = "Length"
        process_events()
        view = Gui.ActiveDocument.ActiveView
        width, height = (int(v) for v in view.getSize())
        a, b = legend.entry_of(pvp), legend.entry_of(rvp)
        check("legends: one per coloured object", a is not None and b is not None
              and pvp.Proxy.has_legend() and rvp.Proxy.has_legend())
        if a is None or b is None:
            return
        (_, _, a0, a1), (_, _, b0, b1) = a["bar"], b["bar"]
        a_top = max([a1] + [y for _, _, y, _ in a["labels"]])
        b_top = max([b1] + [y for _, _, y, _ in b["labels"]])
        a_low = min([a0] + [y for _, _, y, _ in a["labels"]])
        check("legends: stacked, never overprinting", a_low > b_top or min(
            [b0] + [y for _, _, y, _ in b["labels"]]) > a_top, f"{a['bar']} {b['bar']}")
        # Within a legend, no two texts closer than a text line (13 px font).
        closest = min(abs(p[2] - q[2]) for e in (a, b) for i, p in enumerate(e["labels"])
                      for q in e["labels"][i + 1:])
        check("legends: title and values never overprint", closest * height / 2.0 >= 14.0,
              f"closest {closest * height / 2.0:.1f} px")
        # The cube: 132 px in the top-right corner by default (FreeCAD 0.20).
        cube_bottom = 1.0 - 2.0 * 132 / height
        check("legends: below the navigation cube", max(a_top, b_top) + 2.0 * 8 / height
              < cube_bottom, f"top {max(a_top, b_top):.3f} vs cube {cube_bottom:.3f} ({height} px)")

        # Readable: the label colour against the background rendered beside it.
        path = os.path.join(tempfile.mkdtemp(), "legend.png")
        # The model moved out of sight (the camera far aside), so the pixels
        # beside each label are the background itself.
        cam = view.getCameraNode()
        kept = cam.position.getValue()
        from pivy import coin

        cam.position.setValue(kept + coin.SbVec3f(1e9, 1e9, 0))
        view.saveImage(path, width, height, "Current")
        cam.position.setValue(kept)
        image = QtGui.QImage(path)
        worst, worst_at = 99.0, None
        for entry in (a, b):
            for text, _x, y, rgb in entry["labels"]:
                bg = rendered_pixel(image, 0.985, y)  # right of the bar: only background
                c = legend.contrast(rgb, bg)
                if c < worst:
                    worst, worst_at = c, (text, round(y, 3), rgb, bg, legend.background_at(y))
        check("legends: every label contrasts with the rendered background (>= 4.5)",
              worst >= 4.5, f"lowest contrast {worst:.2f} at {worst_at}")
        texts = [t for t, *_ in a["labels"]] + [t for t, *_ in b["labels"]]
        check("legends: lengths in mm under the Standard schema",
              all(t.endswith(" mm") for t in texts[1:4] + texts[5:8]), str(texts))
        FreeCAD.Units.setSchema(1)  # MKS: rods of ~1.5 m read in m
        rvp.ColorBy = "Shape"
        rvp.ColorBy = "Length"
        process_events()
        rod_texts = [t for t, *_ in legend.entry_of(rvp)["labels"]][1:]
        lengths = list(kids["Rods"].RodLengths)
        check("legends: rod lengths in m under MKS", all(t.endswith(" m") for t in rod_texts)
              and abs(float(rod_texts[0].split()[0]) - max(lengths) / 1000.0) < 1e-3 * max(lengths),
              f"{rod_texts} (longest {max(lengths):.1f} mm)")
        FreeCAD.Units.setSchema(schema)

        kids["Panels"].ViewObject.Visibility = False
        process_events()
        check("legends: a hidden object's legend goes", not pvp.Proxy.has_legend())
        moved = legend.entry_of(rvp)
        check("legends: the others close up", moved is not None and moved["bar"][3] > b1,
              f"{moved and moved['bar']} vs {b['bar']}")
        kids["Panels"].ViewObject.Visibility = True
        process_events()
        check("legends: shown again with its object", pvp.Proxy.has_legend())
        # As Std_Delete does: the view provider's onDelete, then the removal.
        parent.ViewObject.Proxy.onDelete(parent.ViewObject, [])
        doc.removeObject(parent.Name)
        process_events()
        left = [n for n in legend._LEGENDS if n[0] == doc.Name]
        check("legends: deleting the Panelization removes its legends", not left, str(left))
    finally:
        FreeCAD.Units.setSchema(schema)
        FreeCAD.closeDocument(doc.Name)


def test_id_labels_and_unfold_beside():
    import freecad_workbench as tessella
    from freecad_workbench.features.panelization import children_of

    ensure_workbench()
    doc = FreeCAD.newDocument("TessellaIdLabels")
    try:
        parent, kids = panelized_surface(doc)
        for role, ids in (("Panels", "PanelIds"), ("Rods", "RodIds"), ("Nodes", "NodeIds")):
            vobj = kids[role].ViewObject
            check(f"labels: {role} off by default", "ShowIds" in vobj.PropertiesList
                  and not vobj.ShowIds and vobj.Proxy.id_labels.texts() == [])
            vobj.ShowIds = True
            process_events()
            texts = vobj.Proxy.id_labels.texts()
            check(f"labels: {role} one per item, the schedule's IDs",
                  texts == list(getattr(kids[role], ids)) and len(texts) > 10,
                  f"{len(texts)} labels, {len(getattr(kids[role], ids))} IDs")
        # Each panel label sits inside its panel's bounding box (independently: FreeCAD's box).
        labels = kids["Panels"].ViewObject.Proxy.id_labels
        items = labels.label_nodes()
        faces = kids["Panels"].Shape.childShapes()
        inside = 0
        for item, face in zip(items, faces):
            x, y, z = item.getChild(0).translation.getValue().getValue()
            inside += face.BoundBox.isInside(FreeCAD.Vector(x, y, z))
        check("labels: every panel label inside its panel", inside == len(faces),
              f"{inside} of {len(faces)}")
        parent.Size = 2500.0
        doc.recompute()
        process_events()
        check("labels: follow a recompute", labels.texts() == list(kids["Panels"].PanelIds)
              and len(labels.texts()) == kids["Panels"].Shape.childShapes().__len__(),
              f"{len(labels.texts())} vs {parent.PanelCount}")
        kids["Panels"].ViewObject.Visibility = False
        process_events()
        check("labels: hidden with the object", labels.texts() == [])
        kids["Panels"].ViewObject.Visibility = True
        process_events()
        check("labels: shown again", len(labels.texts()) == parent.PanelCount)

        unfold = tessella.make_unfold(parent)
        process_events()
        model, flat = kids["Panels"].Shape.BoundBox, unfold.Shape.BoundBox
        check("unfold: beside the model, not over it", flat.XMin > model.XMax
              and not flat.intersect(model), f"unfold {flat} model {model}")
        Gui.SendMsgToActiveView("ViewFit")
        process_events()

        from pivy import coin

        def labels_in_scene():
            search = coin.SoSearchAction()
            search.setName("TessellaIdLabels")
            search.setInterest(coin.SoSearchAction.ALL)
            search.apply(Gui.ActiveDocument.ActiveView.getSceneGraph())
            return search.getPaths().getLength()

        check("labels: three label sets in the scene", labels_in_scene() == 3, str(labels_in_scene()))
        parent.ViewObject.Proxy.onDelete(parent.ViewObject, [])
        for name in [unfold.Name] + [c.Name for c in children_of(parent)] + [parent.Name]:
            if doc.getObject(name) is not None:
                doc.removeObject(name)
        process_events()
        check("labels: gone with the object", labels_in_scene() == 0, str(labels_in_scene()))
    finally:
        FreeCAD.closeDocument(doc.Name)


# FreeCAD runs this file as a script: run the tests, write the result, quit.
ensure_workbench()
gui_harness.run("Tessella display GUI test", (test_legends, test_id_labels_and_unfold_beside),
                "tessella_gui_display_result.json")
