"""Colour-bar legends of the analysis colours, laid out as FreeCAD users expect.

One legend per coloured object, in the 3D view's right margin: stacked top to
bottom in slots (two legends never overprint), below the navigation cube when
the cube sits in a right corner (above it in the bottom corner), hidden with
its object, gone with it. Values are written in the unit the user's unit
schema picks for the largest one (mm or m for lengths, mm² ... m² for areas),
and each label is black or white, whichever contrasts more with the view's
background behind it (the preference colours, simple or gradient).

The legend draws in normalized view coordinates (x, y in [-1, 1]) under its own
orthographic camera (viewport mapping LEAVE_ALONE), so it stays put when the
model camera moves; its height in pixels comes from the view's size.
"""

import FreeCAD

#: Right margin of the view taken by the bars (normalized x).
BAR_X0, BAR_X1 = 0.90, 0.94
#: Pixels kept free around the navigation cube.
CUBE_MARGIN_PX = 16
#: Background colours of FreeCAD 0.20 when the user never changed them (read
#: off an empty view: top 0x333365, bottom 0xABABC1) and the 132-px cube.
DEFAULT_TOP, DEFAULT_BOTTOM = (51, 51, 101), (171, 171, 193)
DEFAULT_SIMPLE = (51, 51, 101)
DEFAULT_CUBE_PX = 132

_VIEW_PARAMS = "User parameter:BaseApp/Preferences/View"

# Live legends in the order they were shown: (document name, object name) -> entry.
_LEGENDS = {}


# ----------------------------------------------------------------- values
def display_scale(unit, lo, hi):
    """(factor, unit label) for values in `unit` ("mm", "m²", or anything else,
    shown as is): the unit the user's schema picks for the largest magnitude;
    a value v is shown as v / factor."""
    Units = FreeCAD.Units
    biggest = max(abs(lo), abs(hi))
    if unit == "mm":
        q = Units.Quantity(biggest or 1.0, Units.Length)
        _text, factor, label = q.getUserPreferred()
        return float(factor), label
    if unit == "m²":  # values come in m² (analysis_colors.values_for)
        q = Units.Quantity((biggest or 1.0) * 1e6, Units.Area)
        _text, factor, label = q.getUserPreferred()
        return float(factor) / 1e6, label.replace("^2", "²")
    return 1.0, unit


def format_value(value, factor, label):
    text = f"{value / factor:.4g}"
    return f"{text} {label}" if label and label != "type" else text


# ------------------------------------------------------------- background
def _rgb(packed):
    return ((packed >> 24) & 255, (packed >> 16) & 255, (packed >> 8) & 255)


def _pack(rgb):
    return (rgb[0] << 24) | (rgb[1] << 16) | (rgb[2] << 8) | 255


def background_at(y):
    """The view background (0-255 RGB) at normalized height y (1 = top), from the
    user's View preferences (simple colour, or the top / middle / bottom gradient)."""
    p = FreeCAD.ParamGet(_VIEW_PARAMS)
    if p.GetBool("Simple", False) or not p.GetBool("Gradient", True):
        return _rgb(p.GetUnsigned("BackgroundColor", _pack(DEFAULT_SIMPLE)))
    top = _rgb(p.GetUnsigned("BackgroundColor2", _pack(DEFAULT_TOP)))
    bottom = _rgb(p.GetUnsigned("BackgroundColor3", _pack(DEFAULT_BOTTOM)))
    t = min(max((1.0 - y) / 2.0, 0.0), 1.0)  # 0 at the top, 1 at the bottom
    if p.GetBool("UseBackgroundColorMid", False):
        mid = _rgb(p.GetUnsigned("BackgroundColor4", _pack(DEFAULT_TOP)))
        a, b, t = (top, mid, 2 * t) if t < 0.5 else (mid, bottom, 2 * t - 1)
    else:
        a, b = top, bottom
    return tuple(round(a[i] + (b[i] - a[i]) * t) for i in range(3))


def _luminance(rgb):
    def lin(c):
        c = c / 255.0
        return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4

    r, g, b = (lin(c) for c in rgb)
    return 0.2126 * r + 0.7152 * g + 0.0722 * b


def contrast(a, b):
    """WCAG contrast ratio of two 0-255 RGB colours (1 to 21)."""
    la, lb = sorted((_luminance(a), _luminance(b)), reverse=True)
    return (la + 0.05) / (lb + 0.05)


def text_color_for(background):
    """Black or white (0-255 RGB), whichever contrasts more with `background`."""
    black, white = (0, 0, 0), (255, 255, 255)
    return black if contrast(black, background) >= contrast(white, background) else white


# ----------------------------------------------------------------- layout
def _view_height_px():
    try:
        import FreeCADGui as Gui

        view = Gui.ActiveDocument.ActiveView
        return max(int(view.getSize()[1]), 100)
    except Exception:
        return 600


def free_band(height_px):
    """(y_bottom, y_top) of the right margin free of the navigation cube."""
    p = FreeCAD.ParamGet(_VIEW_PARAMS)
    lo, hi = -0.95, 0.95
    if p.GetBool("ShowNaviCube", True):
        corner = p.GetInt("CornerNaviCube", 1)  # 0 top left, 1 top right, 2/3 bottom
        size = p.GetInt("NaviWidgetSize", DEFAULT_CUBE_PX)
        reach = 2.0 * (size + CUBE_MARGIN_PX) / height_px
        if corner == 1:
            hi = min(hi, 1.0 - reach)
        elif corner == 3:
            lo = max(lo, -1.0 + reach)
    return lo, hi


def slots(count, height_px):
    """(title_y, bar_top, bar_bottom) of each of `count` stacked legends."""
    lo, hi = free_band(height_px)
    line = 2.0 * 16 / height_px  # one text line (16 px) in normalized view units
    each = (hi - lo) / max(count, 1)
    each = min(each, 0.9)
    out = []
    for k in range(count):
        top = hi - k * each
        # The title on the first line; the top value, centred on the bar's top,
        # starts a tenth of a line below it; the bottom value, centred on the
        # bar's bottom, ends above the next slot.
        out.append((top - 0.5 * line, top - 1.6 * line, top - each + 0.6 * line))
    return out


# ------------------------------------------------------------------ scene
def _key(vobj):
    obj = vobj.Object
    return (obj.Document.Name, obj.Name)


def _alive(entry):
    vobj = entry["vobj"]
    try:
        obj = vobj.Object
        return obj.Document.getObject(obj.Name) is not None
    except Exception:
        return False


def show(vobj, title, lo, hi, unit, colors):
    """Show (or replace) the legend of `vobj`: `colors(values, lo, hi)` gives
    the bar's colours."""
    hide(vobj)
    factor, label = display_scale(unit, lo, hi)
    _LEGENDS[_key(vobj)] = {"vobj": vobj, "title": title, "lo": lo, "hi": hi, "unit": unit,
                            "factor": factor, "label": label, "colors": colors, "node": None,
                            "labels": []}
    relayout()


def hide(vobj):
    """Remove the legend of `vobj` (if any); the others close up."""
    entry = _LEGENDS.pop(_key(vobj), None)
    if entry is not None:
        _detach(entry)
        relayout()


def entry_of(vobj):
    """The live legend of `vobj` (a dict: title, labels [(text, x, y, rgb)],
    bar (x0, x1, y_bottom, y_top)) or None: for tests and screenshots."""
    entry = _LEGENDS.get(_key(vobj))
    if entry is None or entry["node"] is None:
        return None
    return entry


def _detach(entry):
    node = entry.get("node")
    vobj = entry["vobj"]
    if node is not None:
        try:
            if vobj.RootNode.findChild(node) >= 0:
                vobj.RootNode.removeChild(node)
        except Exception:
            pass  # the object is gone, and its scene with it
    entry["node"] = None


def relayout():
    """Rebuild every live, visible legend in its slot."""
    for key in [k for k, e in _LEGENDS.items() if not _alive(e)]:
        _LEGENDS.pop(key)
    shown = []
    for entry in _LEGENDS.values():
        _detach(entry)
        if entry["vobj"].Visibility:
            shown.append(entry)
    height = _view_height_px()
    for entry, slot in zip(shown, slots(len(shown), height)):
        _build(entry, slot)


def _build(entry, slot):
    try:
        from pivy import coin
    except ImportError:
        return
    title_y, y1, y0 = slot
    lo, hi = entry["lo"], entry["hi"]
    hud = coin.SoSeparator()
    hud.setName("TessellaLegend")
    cam = coin.SoOrthographicCamera()
    cam.viewportMapping = coin.SoCamera.LEAVE_ALONE
    cam.position = coin.SbVec3f(0, 0, 5)
    cam.height = 2.0
    hud.addChild(cam)
    light = coin.SoLightModel()
    light.model = coin.SoLightModel.BASE_COLOR
    hud.addChild(light)
    if hasattr(coin, "SoDepthBuffer"):  # drawn over the model, never behind it
        depth = coin.SoDepthBuffer()
        depth.test = False
        hud.addChild(depth)
    steps = 16
    coords = coin.SoCoordinate3()
    points = []
    for k in range(steps):
        ya = y0 + (y1 - y0) * k / steps
        yb = y0 + (y1 - y0) * (k + 1) / steps
        points += [(BAR_X0, ya, 0), (BAR_X1, ya, 0), (BAR_X1, yb, 0), (BAR_X0, yb, 0)]
    coords.point.setValues(0, len(points), points)
    material = coin.SoMaterial()
    bar = entry["colors"]([lo + (hi - lo) * (k + 0.5) / steps for k in range(steps)], lo, hi)
    material.diffuseColor.setValues(0, steps, bar)
    binding = coin.SoMaterialBinding()
    binding.value = coin.SoMaterialBinding.PER_FACE
    faces = coin.SoFaceSet()
    faces.numVertices.setValues(0, steps, [4] * steps)
    for node in (coords, material, binding, faces):
        hud.addChild(node)
    f, unit = entry["factor"], entry["label"]
    labels = [(entry["title"], BAR_X1, title_y)]
    # Below the kernel's confusion (1e-7 mm) a length reads 0, not 1.5e-11 mm.
    shown = (lambda v: 0.0 if abs(v) < 1e-6 else v) if entry["unit"] == "mm" else (lambda v: v)
    labels += [(format_value(shown(v), f, unit), BAR_X0 - 0.015, y)
               for v, y in ((hi, y1), (0.5 * (lo + hi), 0.5 * (y0 + y1)), (lo, y0))]
    placed = []
    for text_value, x, y in labels:
        rgb = text_color_for(background_at(y))
        sep = coin.SoSeparator()
        color = coin.SoBaseColor()
        color.rgb = tuple(c / 255.0 for c in rgb)
        move = coin.SoTranslation()
        # SoText2's base line sits at y: centre the label on its height.
        move.translation = (x, y - 0.01, 0)
        text = coin.SoText2()
        text.string = text_value
        text.justification = coin.SoText2.RIGHT
        for node in (color, move, text):
            sep.addChild(node)
        hud.addChild(sep)
        placed.append((text_value, x, y, rgb))
    entry["vobj"].RootNode.addChild(hud)
    entry["node"] = hud
    entry["labels"] = placed
    entry["bar"] = (BAR_X0, BAR_X1, y0, y1)
