// Bindings of the fabrication area: unfold, nest, outline offset.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "tessella/errors.h"
#include "tessella/face_set.h"
#include "tessella/flatten.h"
#include "tessella/nest.h"
#include "tessella/outline_offset.h"
#include "tessella/panel_mesh.h"
#include "tessella/surface_face.h"
#include "tessella/unfold.h"

namespace py = pybind11;
using namespace tessella;

namespace {

py::array_t<double> rows2(const std::vector<Vec2>& v) {
  py::array_t<double> a({static_cast<py::ssize_t>(v.size()), py::ssize_t(2)});
  auto m = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < v.size(); ++i) m(i, 0) = v[i].x(), m(i, 1) = v[i].y();
  return a;
}

std::vector<Vec2> from_rows2(
    const py::array_t<double, py::array::c_style | py::array::forcecast>& a) {
  if (a.ndim() != 2 || a.shape(1) != 2) throw InvalidParameter("an outline must be a (k,2) array");
  auto r = a.unchecked<2>();
  std::vector<Vec2> out;
  for (py::ssize_t i = 0; i < r.shape(0); ++i) out.emplace_back(r(i, 0), r(i, 1));
  return out;
}

}  // namespace

void bind_fabrication(py::module_& m) {
  py::class_<UnfoldParams>(m, "UnfoldParams")
      .def(py::init<>())
      .def_readwrite("fold_tolerance_deg", &UnfoldParams::fold_tolerance_deg);
  py::class_<Fold>(m, "Fold")
      .def_readonly("a", &Fold::a)
      .def_readonly("b", &Fold::b)
      .def_readonly("angle_deg", &Fold::angle_deg);
  py::class_<FlatPanel>(m, "FlatPanel")
      .def_property_readonly("outline", [](const FlatPanel& f) { return rows2(f.outline); })
      .def_readonly("folds", &FlatPanel::folds)
      .def_readonly("max_fold_deg", &FlatPanel::max_fold_deg)
      .def_readonly("triangles", &FlatPanel::triangles)
      .def_readonly("self_intersecting", &FlatPanel::self_intersecting)
      .def_property_readonly("u_direction", [](const FlatPanel& f) {
        return py::make_tuple(f.u_direction.x(), f.u_direction.y());
      });
  m.def("unfold_panels", [](const PanelMesh& mesh, const UnfoldParams& p) {
    py::gil_scoped_release release;
    return unfold_panels(mesh, p);
  });
  m.def("fold_angle_deg", &fold_angle_deg);

  py::class_<FlattenParams>(m, "FlattenParams")
      .def(py::init<>())
      .def_readwrite("subdivisions", &FlattenParams::subdivisions);
  py::class_<FlatPatch>(m, "FlatPatch")
      .def_property_readonly("outline", [](const FlatPatch& f) { return rows2(f.outline); })
      .def_readonly("corner_index", &FlatPatch::corner_index)
      .def_readonly("strain_max", &FlatPatch::strain_max)
      .def_readonly("strain_mean", &FlatPatch::strain_mean)
      .def_readonly("area_3d", &FlatPatch::area_3d)
      .def_property_readonly("u_direction", [](const FlatPatch& f) {
        return py::make_tuple(f.u_direction.x(), f.u_direction.y());
      });
  m.def("flatten_panels", [](const SurfaceFace& f, const PanelMesh& mesh, const FlattenParams& p) {
    py::gil_scoped_release release;
    return flatten_panels(f, mesh, p);
  });
  m.def("flatten_face_set_panels", [](const FaceSet& set, const PanelMesh& mesh,
                                      const std::vector<int>& panel_face, const FlattenParams& p) {
    py::gil_scoped_release release;
    return flatten_face_set_panels(set, mesh, panel_face, p);
  });

  py::class_<NestParams>(m, "NestParams")
      .def(py::init<>())
      .def_readwrite("sheet_width", &NestParams::sheet_width)
      .def_readwrite("sheet_height", &NestParams::sheet_height)
      .def_readwrite("margin", &NestParams::margin)
      .def_readwrite("spacing", &NestParams::spacing)
      .def_readwrite("rotations", &NestParams::rotations)
      .def_readwrite("resolution", &NestParams::resolution)
      .def_readwrite("max_sheets", &NestParams::max_sheets);
  py::class_<NestPlacement>(m, "NestPlacement")
      .def_readonly("sheet", &NestPlacement::sheet)
      .def_readonly("angle_deg", &NestPlacement::angle_deg)
      .def_property_readonly("offset", [](const NestPlacement& p) {
        return py::make_tuple(p.offset.x(), p.offset.y());
      });
  py::class_<NestLayout>(m, "NestLayout")
      .def_readonly("placements", &NestLayout::placements)
      .def_readonly("sheet_count", &NestLayout::sheet_count)
      .def_readonly("sheet_utilization", &NestLayout::sheet_utilization)
      .def_readonly("utilization", &NestLayout::utilization);
  m.def(
      "nest_parts",
      [](const std::vector<py::array_t<double, py::array::c_style | py::array::forcecast>>&
             outlines,
         const NestParams& p, const std::vector<std::string>& names) {
        std::vector<std::vector<Vec2>> parts;
        for (const auto& o : outlines) parts.push_back(from_rows2(o));
        py::gil_scoped_release release;
        return nest_parts(parts, p, names);
      },
      py::arg("outlines"), py::arg("params"), py::arg("names") = std::vector<std::string>{});

  py::class_<OutlineOffsetParams>(m, "OutlineOffsetParams")
      .def(py::init<>())
      .def_readwrite("distance", &OutlineOffsetParams::distance)
      .def_readwrite("resolution", &OutlineOffsetParams::resolution)
      .def_readwrite("round_corners", &OutlineOffsetParams::round_corners)
      .def_readwrite("arc_tolerance", &OutlineOffsetParams::arc_tolerance);
  m.def("offset_outline",
        [](const py::array_t<double, py::array::c_style | py::array::forcecast>& outline,
           const OutlineOffsetParams& p) { return rows2(offset_outline(from_rows2(outline), p)); });
}
