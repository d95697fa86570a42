"""View provider of the Unfold feature.

FROZEN: the module path `freecad_workbench.gui.unfold_view` and the class name
`ViewProviderUnfold` are stored in the GuiDocument.xml of saved .FCStd files.
"""

from .common import icon_path
from .view_providers import _VPState


class ViewProviderUnfold(_VPState):
    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        self.ViewObject = vobj
        self.Object = vobj.Object

    def getIcon(self):
        return icon_path("Tessella_Unfold")

    def updateData(self, obj, prop):
        return None

    def onChanged(self, vobj, prop):
        return None
