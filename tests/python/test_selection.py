"""freecad_workbench.selection: every accepted form of "a face" and "edges", and
every error, with the messages the callers have always given."""
import FreeCAD
import Part
import pytest

import freecad_workbench as tessella
from freecad_workbench import api, selection


class FakeSelection:
    """What Gui.Selection.getSelectionEx() returns (Object + SubElementNames)."""

    def __init__(self, obj, *names):
        self.Object = obj
        self.ObjectName = obj.Name
        self.SubElementNames = tuple(names)


@pytest.fixture
def doc():
    d = FreeCAD.newDocument("SelectionTest")
    yield d
    FreeCAD.closeDocument(d.Name)


@pytest.fixture
def objs(doc):
    plate = doc.addObject("Part::Feature", "Plate")
    plate.Shape = Part.makePlane(3000, 2000)
    box = doc.addObject("Part::Feature", "Box")
    box.Shape = Part.makeBox(3000, 2000, 1000)
    line = doc.addObject("Part::Feature", "Line")
    line.Shape = Part.makeLine((0, 0, 0), (1000, 0, 0))
    poly = doc.addObject("Part::Feature", "Poly")
    poly.Shape = Part.makePolygon([FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(1000, 0, 0),
                                   FreeCAD.Vector(1000, 800, 0)])
    empty = doc.addObject("Part::Feature", "Empty")
    group = doc.addObject("App::DocumentObjectGroup", "Group")
    doc.recompute()
    return dict(plate=plate, box=box, line=line, poly=poly, empty=empty, group=group)


def _same(a, b):
    return a.isSame(b) or a.exportBrepToString() == b.exportBrepToString()


# --------------------------------------------------------------------- faces
def test_one_face_accepts_every_form(objs):
    box, plate = objs["box"], objs["plate"]
    top = box.Shape.Faces[5]
    for form in (top, Part.Shell([top]), Part.Compound([top]), (box, "Face6"), [box, "Face6"],
                 (box, ["Face6"]), (box, ("Face6",)), FakeSelection(box, "Face6"),
                 [FakeSelection(box, "Face6")], [(box, "Face6")]):
        face = selection.one_face(form)
        assert face.ShapeType == "Face" and _same(face, top), form
    # a one-face object, alone, in a pair without sub-elements, or selected whole
    for form in (plate, (plate, []), (plate, ""), FakeSelection(plate)):
        assert _same(selection.one_face(form), plate.Shape.Faces[0]), form
    # the API and the feature path give the same bytes as before
    assert api.face_to_brep(plate) == api.face_to_brep(plate.Shape)
    assert api.face_to_shape((box, "Face6")).Area == pytest.approx(6e6)


@pytest.mark.parametrize("form, error, match", [
    (lambda o: (o["box"], "Edge1"), ValueError, "not a face"),
    (lambda o: (o["box"], "Vertex2"), ValueError, "not a face"),
    (lambda o: (o["box"], "Face99"), ValueError, "Box has no Face99"),
    (lambda o: o["box"].Shape, ValueError, "the shape has 6 faces"),
    (lambda o: Part.makeLine((0, 0, 0), (1, 0, 0)), ValueError, "0 faces"),
    (lambda o: Part.Shape(), ValueError, "the shape is empty"),
    (lambda o: o["box"], ValueError, "'Box' has 6 faces: pass \\(object, 'FaceN'\\)"),
    (lambda o: (o["box"], ["Face1", "Face2"]), ValueError,
     "select exactly one face, got sub-elements \\['Face1', 'Face2'\\]"),
    (lambda o: [FakeSelection(o["box"], "Face1"), FakeSelection(o["plate"], "Face1")],
     ValueError, "select exactly one face, got 2 selections"),
    (lambda o: [], ValueError, "nothing given"),
    (lambda o: o["empty"], ValueError, "'Empty' has no shape"),
    (lambda o: (o["group"], "Face1"), ValueError, "'Group' has no shape"),
    (lambda o: "Face1", TypeError, "face must be"),
    (lambda o: 42, TypeError, "face must be"),
    (lambda o: (o["box"], 5), TypeError, "sub-element must be a name like 'Face1'"),
])
def test_one_face_errors(objs, form, error, match):
    with pytest.raises(error, match=match):
        selection.one_face(form(objs))


def test_faces_of(objs):
    box, plate = objs["box"], objs["plate"]
    assert len(selection.faces_of(box)) == 6
    assert len(selection.faces_of(box.Shape)) == 6
    assert len(selection.faces_of(Part.Shell(box.Shape.Faces[:3]))) == 3
    assert len(selection.faces_of([(box, ["Face1", "Face2"]), plate])) == 3
    assert len(selection.faces_of(FakeSelection(box, "Face1", "Face3"))) == 2
    assert selection.faces_of([]) == []
    with pytest.raises(ValueError, match="not a face"):
        selection.faces_of((box, "Edge1"))
    with pytest.raises(ValueError, match="no faces"):
        selection.faces_of(objs["line"])
    with pytest.raises(ValueError, match="no faces"):
        selection.faces_of(objs["line"].Shape)
    with pytest.raises(ValueError, match="empty"):
        selection.faces_of(Part.Shape())
    with pytest.raises(TypeError):
        selection.faces_of([box, 3.5])


def test_face_link(objs):
    box, plate = objs["box"], objs["plate"]
    for form in ((box, "Face6"), [box, "Face6"], (box, ["Face6"]), FakeSelection(box, "Face6"),
                 [FakeSelection(box, "Face6")]):
        assert selection.face_link(form) == (box, "Face6")
    for form in (plate, (plate, ()), FakeSelection(plate)):
        assert selection.face_link(form) == (plate, "Face1")
    with pytest.raises(TypeError, match="source must be a document object"):
        selection.face_link(plate.Shape.Faces[0])
    with pytest.raises(TypeError, match="source must be a document object"):
        selection.face_link("Face1")
    with pytest.raises(ValueError, match="'Box' has 6 faces"):
        selection.face_link(box)
    with pytest.raises(ValueError, match="select exactly one face"):
        selection.face_link(FakeSelection(box, "Face1", "Face2"))
    with pytest.raises(ValueError, match="not a face"):
        selection.face_link(FakeSelection(box, "Edge1"))
    with pytest.raises(ValueError, match="Box has no Face7"):
        selection.face_link((box, "Face7"))
    with pytest.raises(ValueError, match="^P: Source: 'Empty' has no shape"):
        selection.face_link(objs["empty"], context="P: Source")


# --------------------------------------------------------------------- edges
def test_edges_of_accepts_every_form(objs):
    box, line, poly = objs["box"], objs["line"], objs["poly"]
    e1 = box.Shape.Edges[0]
    assert [c.ShapeType for c in selection.edges_of(e1)] == ["Edge"]
    assert [c.ShapeType for c in selection.edges_of(poly.Shape)] == ["Wire"]  # one curve
    assert [c.ShapeType for c in selection.edges_of(Part.Compound([e1]))] == ["Edge"]
    assert [c.ShapeType for c in selection.edges_of(Part.Wire([e1]))] == ["Wire"]
    assert [c.ShapeType for c in selection.edges_of(line)] == ["Edge"]
    assert len(selection.edges_of(poly)) == 1
    for form in ((box, "Edge1"), [box, "Edge1"], (box, ["Edge1"]), FakeSelection(box, "Edge1"),
                 [(box, "Edge1")]):
        curves = selection.edges_of(form)
        assert len(curves) == 1 and _same(curves[0], e1), form
    assert len(selection.edges_of((box, ["Edge1", "Edge2"]))) == 2
    assert len(selection.edges_of([(box, "Edge1"), line, e1])) == 3
    assert len(selection.edges_of(FakeSelection(box, "Edge1", "Edge4"))) == 2
    assert len(selection.edges_of([(box, ("Edge1",)), (line, ())])) == 2  # a LinkSubList value
    assert selection.edges_of([]) == []
    assert _same(selection.one_edge((box, "Edge3")), box.Shape.Edges[2])
    assert selection.one_edge(poly).ShapeType == "Wire"


@pytest.mark.parametrize("form, match", [
    (lambda o: (o["box"], "Face1"), "^guides: Box.Face1 is not an edge"),
    (lambda o: (o["box"], "Edge99"), "^guides: Box has no Edge99"),
    (lambda o: o["box"], "^guides: each guide must be one edge or one wire"),
    (lambda o: o["box"].Shape, "each guide must be one edge or one wire"),
    (lambda o: Part.Shape(), "^guides: the shape is empty"),
    (lambda o: o["empty"], "^guides: 'Empty' has no shape"),
    (lambda o: o["group"], "'Group' has no shape"),
    (lambda o: [42], "^guides: expected Part.Edge objects, got int"),
    (lambda o: "Edge1", "expected Part.Edge objects, got str"),
])
def test_edges_of_errors(objs, form, match):
    with pytest.raises(ValueError, match=match):
        selection.edges_of(form(objs))


def test_one_edge_needs_exactly_one(objs):
    with pytest.raises(ValueError, match="expected one edge, got 2"):
        selection.one_edge((objs["box"], ["Edge1", "Edge2"]))
    with pytest.raises(ValueError, match="^X: expected one edge, got 0"):
        selection.one_edge([], context="X")


def test_edge_links(objs):
    box, line = objs["box"], objs["line"]
    assert selection.edge_links((box, "Edge1")) == [(box, "Edge1")]
    assert selection.edge_links([(box, ["Edge1", "Edge2"]), line]) == [
        (box, "Edge1"), (box, "Edge2"), (line, "")]
    assert selection.edge_links(FakeSelection(box, "Edge5")) == [(box, "Edge5")]
    assert selection.link_sub_list([(box, "Edge1"), (line, "")]) == [(box, ["Edge1"]),
                                                                      (line, [""])]
    with pytest.raises(ValueError, match="EdgeN"):
        selection.edge_links([line.Shape])
    with pytest.raises(ValueError, match="EdgeN"):
        selection.edge_links(box.Shape.Edges[0])
    with pytest.raises(ValueError, match="not an edge"):
        selection.edge_links((box, "Face1"))
    with pytest.raises(ValueError, match="has no Edge77"):
        selection.edge_links((box, "Edge77"))


def test_links_of(objs):
    box, plate = objs["box"], objs["plate"]
    assert selection.links_of([(box, ("Edge1", "Edge2")), (plate, ())]) == [
        (box, "Edge1"), (box, "Edge2"), (plate, "")]
    assert selection.links_of(FakeSelection(plate)) == [(plate, "")]
    assert selection.links_of(plate) == [(plate, "")]
    with pytest.raises(TypeError, match="a link needs a document object"):
        selection.links_of(plate.Shape)


def test_is_element():
    assert selection.is_element("Face3", "Face") and selection.is_element("Edge1", "Edge")
    assert not selection.is_element("Edge1", "Face")
    assert not selection.is_element("", "Face") and not selection.is_element(None, "Face")


# --------------------------------------------------------------- the callers
def test_callers_agree(objs):
    """api, make and the feature take the same forms; the feature's messages name it."""
    box, plate, line = objs["box"], objs["plate"], objs["line"]
    r1 = tessella.panelize(plate, size=1000.0)
    r2 = tessella.panelize((plate, "Face1"), size=1000.0)
    assert len(r1.panels) == len(r2.panels) == 6
    p = tessella.make_panelization((plate, ["Face1"]), size=1000.0)
    assert p.PanelCount == 6 and p.Source[0] == plate
    face_arg, label = p.Proxy.source_face(p)
    assert face_arg == (plate, "Face1") and label == "Plate.Face1"
    p.Source = (box, ["Face1", "Face2"])
    with pytest.raises(ValueError, match="^Panelization: Source: select exactly one face"):
        p.Proxy.source_face(p)
    p.Source = (box, [])
    with pytest.raises(ValueError, match="^Panelization: Source: 'Box' has 6 faces"):
        p.Proxy.source_face(p)
    p.Guides = [(box, ["Face1"])]
    with pytest.raises(ValueError, match="^Panelization: Guides: Box.Face1 is not an edge"):
        p.Proxy.guide_edges(p)
    p.Guides = selection.link_sub_list([(box, "Edge1"), (objs["poly"], "")])
    assert len(p.Guides) == 2  # (object, []) would be dropped by FreeCAD
    assert [c.ShapeType for c in p.Proxy.guide_edges(p)] == ["Edge", "Wire"]
    p.Guides = []
    with pytest.raises(ValueError, match="needs guide edges"):
        p.Proxy.guide_edges(p)
    with pytest.raises(ValueError, match="guides must hold exactly 1"):
        tessella.panelize(plate, method="guide_line_scaling", rod_length=500.0,
                          guides=(box, ["Edge1", "Edge2"]))


def test_panelization_of_and_unfold_of(objs):
    from freecad_workbench.features.panelization import children_of

    plate = objs["plate"]
    p = tessella.make_panelization(plate, size=1000.0)
    q = tessella.make_panelization(plate, size=1500.0)
    kids = children_of(p)
    assert selection.panelization_of([p]) == p
    assert selection.panelization_of(kids) == p  # children count as their parent
    assert selection.panelization_of([p] + kids) == p
    assert selection.panelization_of([p, q]) is None  # more than one
    assert selection.panelization_of([plate]) is None
    assert selection.panelization_of([]) is None
    u = tessella.make_unfold(p)
    assert selection.unfold_of([u]) == u and selection.unfold_of([p]) is None
    assert selection.panelization_of([u]) == p


def test_a_whole_object_guide_is_linked(doc):
    """guides=[document object]: stored as (object, ['']) (FreeCAD drops (object, []))."""
    plate = doc.addObject("Part::Feature", "Roof")
    plate.Shape = Part.makePlane(10000, 8000)
    guide = doc.addObject("Part::Feature", "Guide")
    guide.Shape = Part.makeLine((0, 4000, 0), (10000, 4000, 0))
    doc.recompute()
    p = tessella.make_panelization((plate, "Face1"), method="guide_line_scaling",
                                   guides=[guide], rod_length=1000.0)
    q = tessella.make_panelization((plate, "Face1"), method="guide_line_scaling",
                                   guides=[(guide, "Edge1")], rod_length=1000.0)
    assert p.Guides[0][0] == guide and p.isValid()
    assert p.PanelCount == q.PanelCount > 10
