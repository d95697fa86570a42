"""A document written without the GUI opens displayed as the task panel would leave it.

A document saved by a script or the batch mode has no GuiDocument.xml:
FreeCAD 0.20 opens it with every shape hidden, in default grey, with whatever
camera the last document had. When such a document is opened, once its
objects are restored: each object is shown or hidden as its saved Visibility
says (Document.xml), every Panelization's source object is hidden (as after
OK in the task panel), its Panels are coloured by deviation (with the
legend) and the view is isometric and fitted. A document saved from the GUI
keeps exactly what the user left.
"""

import zipfile

import FreeCAD

_scheduled = set()  # documents whose first view is pending


def has_gui_document(path):
    """Whether the .FCStd at path holds a GuiDocument.xml (saved from the GUI)."""
    try:
        with zipfile.ZipFile(path) as z:
            return "GuiDocument.xml" in z.namelist()
    except (OSError, zipfile.BadZipFile):
        return True  # not a file we can read: leave the display alone


def saved_visibility(path):
    """{object name: Visibility} as written in the .FCStd's Document.xml."""
    import xml.etree.ElementTree as ET

    try:
        with zipfile.ZipFile(path) as z:
            root = ET.fromstring(z.read("Document.xml"))
    except (OSError, KeyError, zipfile.BadZipFile, ET.ParseError):
        return {}
    out = {}
    for data in root.iter("Object"):
        name = data.get("name")
        for prop in data.iter("Property"):
            if prop.get("name") == "Visibility":
                flag = prop.find("Bool")
                if name and flag is not None:
                    out[name] = flag.get("value") == "true"
    return out


def schedule(doc):
    """Arrange the first view of doc after its restore (once per document)."""
    if doc is None or doc.Name in _scheduled or not doc.FileName:
        return
    if has_gui_document(doc.FileName):
        return
    from PySide import QtCore

    _scheduled.add(doc.Name)
    name, visible = doc.Name, saved_visibility(doc.FileName)
    QtCore.QTimer.singleShot(0, lambda: apply(name, visible))


def apply(name, visible=None):
    """Hide sources, colour panels by deviation, isometric view fitted to all."""
    import FreeCADGui as Gui

    from ..features.panelization import children_of, is_panelization

    _scheduled.discard(name)
    doc = FreeCAD.listDocuments().get(name)
    gdoc = Gui.getDocument(name) if doc is not None else None
    if gdoc is None:
        return  # closed before the event loop turned
    for obj_name, shown in (visible or {}).items():
        obj = doc.getObject(obj_name)
        if obj is not None and getattr(obj, "ViewObject", None) is not None:
            obj.ViewObject.Visibility = shown
    for obj in doc.Objects:
        if not is_panelization(obj):
            continue
        for source in obj.Proxy.source_objects(obj):
            if source.ViewObject is not None:
                source.ViewObject.Visibility = False
        for child in children_of(obj):
            vobj = child.ViewObject
            if child.Role == "Panels" and vobj is not None and len(child.Deviation):
                vobj.ColorBy = "Deviation"
    view = getattr(gdoc, "ActiveView", None)
    if view is not None and hasattr(view, "viewIsometric"):
        view.viewIsometric()
        view.fitAll()
