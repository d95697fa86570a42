// Bindings of the boundary-driven method (conversions only).
#include "tessella/boundary_driven.h"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "numpy_convert.h"
#include "tessella/errors.h"

namespace py = pybind11;
using namespace tessella;
using bindings::rows;

void bind_boundary_driven(py::module_& m) {
  py::class_<BoundaryDrivenParams>(m, "BoundaryDrivenParams")
      .def(py::init<>())
      .def_readwrite("size", &BoundaryDrivenParams::size)
      .def_readwrite("rho", &BoundaryDrivenParams::rho)
      .def_readwrite("skew_ratio", &BoundaryDrivenParams::skew_ratio)
      .def_readwrite("smoothing_iterations", &BoundaryDrivenParams::smoothing_iterations)
      .def_readwrite("quadrangulate", &BoundaryDrivenParams::quadrangulate)
      .def_readwrite("trim_deflection", &BoundaryDrivenParams::trim_deflection)
      .def_readwrite("step_fraction", &BoundaryDrivenParams::step_fraction)
      .def_readwrite("corner_angle", &BoundaryDrivenParams::corner_angle_deg)
      .def_readwrite("min_edge_fraction", &BoundaryDrivenParams::min_edge_fraction)
      .def_readwrite("max_panels", &BoundaryDrivenParams::max_panels)
      .def_readwrite("angle_target", &BoundaryDrivenParams::angle_target_deg)
      .def_readwrite("angle_passes", &BoundaryDrivenParams::angle_passes)
      .def_property(
          "source_loops", [](const BoundaryDrivenParams& p) { return p.sources.loops; },
          [](BoundaryDrivenParams& p, const std::vector<int>& v) { p.sources.loops = v; })
      .def_property(
          "extra_curves",
          [](const BoundaryDrivenParams& p) {
            py::list out;
            for (const auto& c : p.sources.extra_curves) out.append(rows<2>(c));
            return out;
          },
          [](BoundaryDrivenParams& p, const py::list& curves) {
            p.sources.extra_curves.clear();
            for (const auto& c : curves)
              p.sources.extra_curves.push_back(
                  bindings::points<2>(bindings::DoubleArray::ensure(c), "an extra source curve"));
          });

  // The intermediate stages, for display and tests: traced curves, the
  // preliminary network (nodes, edges, faces) and the final mesh.
  m.def("boundary_driven_stages", [](const SurfaceFace& f, const BoundaryDrivenParams& p) {
    BoundaryDrivenResult r;
    {
      py::gil_scoped_release release;
      r = boundary_driven_stages(f, p);
    }
    py::dict d;
    py::list curves_uv, curves_xyz, closed;
    for (const BdCurve& c : r.curves) {
      curves_uv.append(rows<2>(c.uv));
      curves_xyz.append(rows<3>(c.xyz));
      closed.append(c.closed);
    }
    d["curves_uv"] = curves_uv;
    d["curves_xyz"] = curves_xyz;
    d["curves_closed"] = closed;
    std::vector<Vec2> nuv;
    std::vector<Vec3> nxyz;
    std::vector<int> nloop;
    std::vector<bool> ncorner;
    for (const BdNode& n : r.network.nodes)
      nuv.push_back(n.uv), nxyz.push_back(n.xyz), nloop.push_back(n.loop),
          ncorner.push_back(n.corner);
    d["network_uv"] = rows<2>(nuv);
    d["network_xyz"] = rows<3>(nxyz);
    d["network_loop"] = nloop;
    d["network_corner"] = ncorner;
    d["network_edges"] = r.network.edges;
    d["network_panels"] = r.network.panels;
    d["removed_triangles"] = r.removed_triangles;
    d["collapsed_edges"] = r.collapsed_edges;
    d["angle_moves"] = r.angle_moves;
    d["mesh"] = std::move(r.mesh);
    return d;
  });
}
