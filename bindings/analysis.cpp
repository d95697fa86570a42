// Bindings of the analysis area: panel types and panel families.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "numpy_convert.h"
#include "tessella/panel_classes.h"
#include "tessella/panel_families.h"
#include "tessella/panel_mesh.h"
#include "tessella/panel_types.h"
#include "tessella/unfold.h"

namespace py = pybind11;
using namespace tessella;
using bindings::DoubleArray;

void bind_analysis(py::module_& m) {
  py::class_<PanelTypeParams>(m, "PanelTypeParams")
      .def(py::init<>())
      .def_readwrite("length_tol", &PanelTypeParams::length_tol)
      .def_readwrite("angle_tol", &PanelTypeParams::angle_tol);
  py::class_<PanelTypes>(m, "PanelTypes")
      .def_property_readonly("type", [](const PanelTypes& t) { return bindings::integers(t.type); })
      .def_property_readonly(
          "representative",
          [](const PanelTypes& t) { return bindings::integers(t.representative); })
      .def_property_readonly("count", &PanelTypes::count);
  // outlines: one (k,2) array per panel; folds: one angle (deg) per panel.
  m.def(
      "panel_types",
      [](const std::vector<DoubleArray>& outlines, const std::vector<double>& folds,
         const PanelTypeParams& p) {
        std::vector<std::vector<Vec2>> corners;
        corners.reserve(outlines.size());
        for (const auto& o : outlines) corners.push_back(bindings::points<2>(o, "an outline"));
        py::gil_scoped_release release;
        return panel_types(corners, folds, p);
      },
      py::arg("outlines"), py::arg("folds"), py::arg("params"));
  // Unfolded panels as unfold_panels returns them.
  m.def(
      "flat_panel_types",
      [](const std::vector<FlatPanel>& flat, const PanelTypeParams& p) {
        py::gil_scoped_release release;
        return panel_types(flat, p);
      },
      py::arg("flat"), py::arg("params"));
  // The panels of a mesh, unfolded with `unfold`.
  m.def(
      "mesh_panel_types",
      [](const PanelMesh& mesh, const UnfoldParams& unfold, const PanelTypeParams& p) {
        py::gil_scoped_release release;
        return panel_types(mesh, unfold, p);
      },
      py::arg("mesh"), py::arg("unfold"), py::arg("params"));

  // Panel classes (tessella/panel_classes.h).
  py::class_<PanelClassParams>(m, "PanelClassParams")
      .def(py::init<>())
      .def_readwrite("flat_tolerance", &PanelClassParams::flat_tolerance)
      .def_readwrite("cold_bend_ratio", &PanelClassParams::cold_bend_ratio)
      .def_readwrite("cold_bend_warp", &PanelClassParams::cold_bend_warp);
  py::class_<PanelClasses>(m, "PanelClasses")
      .def_property_readonly("label",
                             [](const PanelClasses& c) { return bindings::integers(c.label); })
      .def_property_readonly("warp", [](const PanelClasses& c) { return bindings::values(c.warp); })
      .def_property_readonly("limit",
                             [](const PanelClasses& c) { return bindings::values(c.limit); })
      .def_property_readonly("count", [](const PanelClasses& c) {
        return std::vector<int>(c.count.begin(), c.count.end());
      });
  m.def(
      "classify_panels",
      [](const std::vector<DoubleArray>& panels, const PanelClassParams& p) {
        std::vector<std::vector<Vec3>> points;
        points.reserve(panels.size());
        for (const auto& c : panels) points.push_back(bindings::points<3>(c, "a panel's vertices"));
        return classify_panels(points, p);
      },
      py::arg("panels"), py::arg("params"));
  m.def(
      "classify_mesh_panels",
      [](const PanelMesh& mesh, const PanelClassParams& p) { return classify_panels(mesh, p); },
      py::arg("mesh"), py::arg("params"));

  // Panel families (tessella/panel_families.h): panels as (k,3) corner arrays.
  py::class_<PanelFamilyParams>(m, "PanelFamilyParams")
      .def(py::init<>())
      .def_readwrite("tolerance", &PanelFamilyParams::tolerance)
      .def_readwrite("mirror", &PanelFamilyParams::mirror)
      .def_readwrite("max_pairs", &PanelFamilyParams::max_pairs);
  py::class_<PanelFamilies>(m, "PanelFamilies")
      .def_property_readonly("labels",
                             [](const PanelFamilies& f) { return bindings::integers(f.labels); })
      .def_property_readonly("templates",
                             [](const PanelFamilies& f) { return bindings::integers(f.templates); })
      .def_property_readonly("max_error",
                             [](const PanelFamilies& f) { return bindings::values(f.max_error); })
      .def_property_readonly("error",
                             [](const PanelFamilies& f) { return bindings::values(f.error); })
      .def_readonly("twin_radius", &PanelFamilies::twin_radius)
      .def_property_readonly("count", &PanelFamilies::count);
  m.def(
      "panel_families",
      [](const std::vector<DoubleArray>& panels, const PanelFamilyParams& p) {
        std::vector<std::vector<Vec3>> corners;
        corners.reserve(panels.size());
        for (const auto& c : panels) corners.push_back(bindings::points<3>(c, "a panel's corners"));
        py::gil_scoped_release release;
        return panel_families(corners, p);
      },
      py::arg("panels"), py::arg("params"));
  m.def(
      "panel_distance",
      [](const DoubleArray& a, const DoubleArray& b, bool mirror) {
        return panel_distance(bindings::points<3>(a, "panel a"), bindings::points<3>(b, "panel b"),
                              mirror);
      },
      py::arg("a"), py::arg("b"), py::arg("mirror") = true);
}
