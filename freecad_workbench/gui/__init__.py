"""GUI side of Tessella: commands, view providers (imported only when FreeCAD.GuiUp)."""
