// Bindings of the guide-line methods (seed 004): conversions only.
#include "tessella/guide_line_scaling.h"
#include "tessella/two_guide_lines.h"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "tessella/guide_line_diamond.h"
#include "tessella/surface_face.h"

namespace py = pybind11;
using namespace tessella;

namespace {

py::array_t<double> points3(const std::vector<Vec3>& v) {
  py::array_t<double> a({static_cast<py::ssize_t>(v.size()), py::ssize_t(3)});
  auto m = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int k = 0; k < 3; ++k) m(i, k) = v[i][k];
  return a;
}

py::array_t<double> points2(const std::vector<Vec2>& v) {
  py::array_t<double> a({static_cast<py::ssize_t>(v.size()), py::ssize_t(2)});
  auto m = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int k = 0; k < 2; ++k) m(i, k) = v[i][k];
  return a;
}

std::vector<Vec3> to_points(
    const py::array_t<double, py::array::c_style | py::array::forcecast>& a) {
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw py::value_error("guides: a guide polyline must be an (N, 3) array of points");
  auto r = a.unchecked<2>();
  std::vector<Vec3> out;
  for (py::ssize_t i = 0; i < a.shape(0); ++i) out.emplace_back(r(i, 0), r(i, 1), r(i, 2));
  return out;
}

}  // namespace

void bind_guide_lines(py::module_& m) {
  py::class_<GuideLineScalingParams>(m, "GuideLineScalingParams")
      .def(py::init<>())
      .def_property(
          "guide", [](const GuideLineScalingParams& p) { return points3(p.guide); },
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
      .def_readwrite("stagger", &GuideLineScalingParams::stagger)
      .def_readwrite("trim_deflection", &GuideLineScalingParams::trim_deflection)
      .def_readwrite("max_panels", &GuideLineScalingParams::max_panels);

  py::class_<TwoGuideLinesParams>(m, "TwoGuideLinesParams")
      .def(py::init<>())
      .def_property(
          "guides",
          [](const TwoGuideLinesParams& p) {
            return py::make_tuple(points3(p.guide_a), points3(p.guide_b));
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
  m.def("two_guide_lines", [](const SurfaceFace& f, const TwoGuideLinesParams& p) {
    py::gil_scoped_release release;
    return two_guide_lines(f, p);
  });
  m.def("two_guide_lines_curves", [](const SurfaceFace& f, const TwoGuideLinesParams& p) {
    TwoGuideLinesResult r;
    {
      py::gil_scoped_release release;
      r = two_guide_lines_curves(f, p);
    }
    py::list a, b;
    for (const SurfaceCurve& c : r.curves_a)
      a.append(py::make_tuple(points2(c.uv), points3(c.xyz)));
    for (const SurfaceCurve& c : r.curves_b)
      b.append(py::make_tuple(points2(c.uv), points3(c.xyz)));
    return py::make_tuple(std::move(r.mesh), a, b);
  });
  py::class_<GuideLineDiamondParams>(m, "GuideLineDiamondParams")
      .def(py::init<>())
      .def_property(
          "guides",
          [](const GuideLineDiamondParams& p) {
            return py::make_tuple(points3(p.guide_a), points3(p.guide_b));
          },
          [](GuideLineDiamondParams& p,
             const std::vector<py::array_t<double, py::array::c_style | py::array::forcecast>>& g) {
            if (g.size() != 2) throw py::value_error("guides must hold exactly 2 polylines");
            p.guide_a = to_points(g[0]);
            p.guide_b = to_points(g[1]);
          })
      .def_readwrite("rod_length", &GuideLineDiamondParams::rod_length)
      .def_readwrite("advance", &GuideLineDiamondParams::advance)
      .def_readwrite("finish_sweep", &GuideLineDiamondParams::finish_sweep)
      .def_readwrite("triangulate", &GuideLineDiamondParams::triangulate)
      .def_readwrite("guide_tolerance", &GuideLineDiamondParams::guide_tolerance)
      .def_readwrite("max_curves", &GuideLineDiamondParams::max_curves)
      .def_readwrite("trim_deflection", &GuideLineDiamondParams::trim_deflection)
      .def_readwrite("max_panels", &GuideLineDiamondParams::max_panels);
  m.def("guide_line_diamond", [](const SurfaceFace& f, const GuideLineDiamondParams& p) {
    py::gil_scoped_release release;
    return guide_line_diamond(f, p);
  });
  m.def("guide_line_scaling", [](const SurfaceFace& f, const GuideLineScalingParams& p) {
    py::gil_scoped_release release;
    return guide_line_scaling(f, p);
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
      curves.append(py::make_tuple(points2(c.uv), points3(c.xyz)));
    return py::make_tuple(std::move(r.mesh), curves);
  });
}
