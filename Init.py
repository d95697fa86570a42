# Tessella - FreeCAD application (no GUI) initialization.
#
# FreeCAD runs this file with exec() when it finds the repository in a Mod folder,
# after putting the repository root on sys.path, so `import freecad_workbench`
# works in every FreeCAD session (GUI or not). Nothing is imported here on
# purpose: the compiled core is loaded only when a Tessella object is used.
# Document objects are restored through their proxy module paths
# (freecad_workbench.features.panelization), which FreeCAD imports on demand.
