// Bindings of the guide-line methods (seed 004): conversions only.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "numpy_convert.h"
#include "tessella/guide_line_scaling.h"
#include "tessella/surface_face.h"
#include "tessella/two_guide_lines.h"

namespace py = pybind11;
using namespace tessella;
using bindings::DoubleArray;
using bindings::rows;

namespace {
std::vector<Vec3> to_points(const DoubleArray& a) {
  return bindings::points<3>(a, "guides: a guide polyline");
}
}  // namespace

void bind_guide_lines(py::module_& m) {
  py::class_<GuideLineScalingParams>(m, "GuideLineScalingParams")
      .def(py::init<>())
      .def_property(
          "guide", [](const GuideLineScalingParams& p) { return rows<3>(p.guide); },
          [](GuideLineScalingParams& p,
             const py::array_t<double, py::array::c_style | py::array::forcecast>& a) {
            p.guide = to_points(a);
          })
      .def_readwrite("rod_length", &GuideLineScalingParams::rod_length)
      .def_readwrite("advance", &GuideLineScalingParams::advance)
      .def_readwrite("merge_fraction", &GuideLineScalingParams::merge_fraction)
      .def_readwrite("guide_tolerance", &GuideLineScalingParams::guide_tolerance)
      .def_readwrite("max_curves", &GuideLineScalingParams::max_curves)
      .def_readwrite("finish_sweep", &GuideLineScalingParams::finish_sweep)
      .def_readwrite("ends_by_distance", &GuideLineScalingParams::ends_by_distance)
      .def_readwrite("stagger", &GuideLineScalingParams::stagger)
      .def_readwrite("trim_deflection", &GuideLineScalingParams::trim_deflection)
      .def_readwrite("max_panels", &GuideLineScalingParams::max_panels);

  py::class_<TwoGuideLinesParams>(m, "TwoGuideLinesParams")
      .def(py::init<>())
      .def_property(
          "guides",
          [](const TwoGuideLinesParams& p) {
            return py::make_tuple(rows<3>(p.guide_a), rows<3>(p.guide_b));
          },
          [](TwoGuideLinesParams& p,
             const std::vector<py::array_t<double, py::array::c_style | py::array::forcecast>>& g) {
            if (g.size() != 2) throw py::value_error("guides must hold exactly 2 polylines");
            p.guide_a = to_points(g[0]);
            p.guide_b = to_points(g[1]);
          })
      .def_readwrite("rod_length", &TwoGuideLinesParams::rod_length)
      .def_readwrite("triangulate", &TwoGuideLinesParams::triangulate)
      .def_readwrite("boundary_divisions", &TwoGuideLinesParams::boundary_divisions)
      .def_readwrite("map_in_uv", &TwoGuideLinesParams::map_in_uv)
      .def_readwrite("corner_angle", &TwoGuideLinesParams::corner_angle)
      .def_readwrite("guide_tolerance", &TwoGuideLinesParams::guide_tolerance)
      .def_readwrite("max_curves", &TwoGuideLinesParams::max_curves)
      .def_readwrite("trim_deflection", &TwoGuideLinesParams::trim_deflection)
      .def_readwrite("max_panels", &TwoGuideLinesParams::max_panels);
  m.def("two_guide_lines_curves", [](const SurfaceFace& f, const TwoGuideLinesParams& p) {
    TwoGuideLinesResult r;
    {
      py::gil_scoped_release release;
      r = two_guide_lines_curves(f, p);
    }
    py::list a, b;
    for (const SurfaceCurve& c : r.curves_a)
      a.append(py::make_tuple(rows<2>(c.uv), rows<3>(c.xyz)));
    for (const SurfaceCurve& c : r.curves_b)
      b.append(py::make_tuple(rows<2>(c.uv), rows<3>(c.xyz)));
    return py::make_tuple(std::move(r.mesh), a, b);
  });
  // The mesh and the advanced curves [(uv (K,2), xyz (K,3)), ...] in sweep order.
  m.def("guide_line_scaling_curves", [](const SurfaceFace& f, const GuideLineScalingParams& p) {
    GuideLineResult r;
    {
      py::gil_scoped_release release;
      r = guide_line_scaling_curves(f, p);
    }
    py::list curves;
    for (const SurfaceCurve& c : r.curves)
      curves.append(py::make_tuple(rows<2>(c.uv), rows<3>(c.xyz)));
    return py::make_tuple(std::move(r.mesh), curves);
  });
}
