"""GUI side of Tessella: commands, view providers, task panels (used only when
FreeCAD.GuiUp).

Importing this package connects the GUI to the App side: it sets
features.base.view_provider_hook, through which a restored document object
without a view provider (made headless, or by an older version) gets one. The
features never import this package; freecad_workbench/__init__.py imports it
whenever FreeCAD's GUI is up.

The commands are registered by gui/register.py (InitGui.py imports it when the
workbench is first activated); the command modules share gui/common.py and
never import each other.
"""


def attach_view_provider(vobj, class_name):
    """Attach the view provider class `class_name` (view_providers or unfold_view)."""
    from . import first_view, unfold_view, view_providers

    if class_name == "ViewProviderPanelization":  # a restored document without its GUI part
        first_view.schedule(vobj.Object.Document)
    for module in (view_providers, unfold_view):
        cls = getattr(module, class_name, None)
        if isinstance(cls, type):
            return cls(vobj)
    raise LookupError(f"no view provider class {class_name!r}")


def install_hooks():
    """Let the features attach view providers through the GUI (idempotent)."""
    from ..features import base

    base.view_provider_hook = attach_view_provider


install_hooks()
