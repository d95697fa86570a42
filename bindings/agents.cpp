// Bindings of the agent methods: walking_agent, gradient_descent, relaxed_grid,
// plus the surface evaluation counter and the folds of a mesh.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "tessella/grid_methods.h"
#include "tessella/panel_mesh.h"
#include "tessella/relaxed_grid.h"
#include "tessella/surface_face.h"
#include "tessella/walking_agent.h"

namespace py = pybind11;
using namespace tessella;

void bind_agents(py::module_& m) {
  py::class_<WalkingAgentParams>(m, "WalkingAgentParams")
      .def(py::init<>())
      .def_readwrite("max_deviation", &WalkingAgentParams::max_deviation)
      .def_readwrite("max_size", &WalkingAgentParams::max_size)
      .def_readwrite("diagonal_deviation", &WalkingAgentParams::diagonal_deviation)
      .def_readwrite("sample_step", &WalkingAgentParams::sample_step)
      .def_readwrite("start", &WalkingAgentParams::start)
      .def_readwrite("max_refinements", &WalkingAgentParams::max_refinements)
      .def_readwrite("edge_share", &WalkingAgentParams::edge_share)
      .def_readwrite("clip", &WalkingAgentParams::clip);
  py::class_<WalkingAgentReport>(m, "WalkingAgentReport")
      .def(py::init<>())
      .def_readonly("folds", &WalkingAgentReport::folds)
      .def_readonly("inserted_lines", &WalkingAgentReport::inserted_lines)
      .def_readonly("refinement_rounds", &WalkingAgentReport::refinement_rounds)
      .def_readonly("bound_lines", &WalkingAgentReport::bound_lines)
      .def_readonly("max_estimate", &WalkingAgentReport::max_estimate)
      .def_readonly("edge_share", &WalkingAgentReport::edge_share);
  py::class_<GradientDescentParams>(m, "GradientDescentParams")
      .def(py::init<>())
      .def_readwrite("max_deviation", &GradientDescentParams::max_deviation)
      .def_readwrite("sample_step", &GradientDescentParams::sample_step)
      .def_readwrite("max_step", &GradientDescentParams::max_step)
      .def_readwrite("start", &GradientDescentParams::start)
      .def_readwrite("clip", &GradientDescentParams::clip);
  py::class_<RelaxedGridParams>(m, "RelaxedGridParams")
      .def(py::init<>())
      .def_readwrite("u_count", &RelaxedGridParams::u_count)
      .def_readwrite("v_count", &RelaxedGridParams::v_count)
      .def_readwrite("max_iterations", &RelaxedGridParams::max_iterations)
      .def_readwrite("tolerance", &RelaxedGridParams::tolerance)
      .def_readwrite("weight", &RelaxedGridParams::weight)
      .def_readwrite("max_panels", &RelaxedGridParams::max_panels);
  py::class_<RelaxedGridReport>(m, "RelaxedGridReport")
      .def(py::init<>())
      .def_readonly("iterations", &RelaxedGridReport::iterations)
      .def_readonly("converged", &RelaxedGridReport::converged)
      .def_readonly("last_move", &RelaxedGridReport::last_move);

  m.def("walking_agent", [](const SurfaceFace& f, const WalkingAgentParams& p) {
    py::gil_scoped_release release;
    return walking_agent(f, p);
  });
  m.def("walking_agent_report", [](const SurfaceFace& f, const WalkingAgentParams& p) {
    WalkingAgentReport r;
    PanelMesh mesh;
    {
      py::gil_scoped_release release;
      mesh = walking_agent(f, p, &r);
    }
    return py::make_tuple(std::move(mesh), r);
  });
  m.def("gradient_descent", [](const SurfaceFace& f, const GradientDescentParams& p) {
    py::gil_scoped_release release;
    return gradient_descent(f, p);
  });
  m.def("relaxed_grid", [](const SurfaceFace& f, const RelaxedGridParams& p) {
    py::gil_scoped_release release;
    return relaxed_grid(f, p);
  });
  m.def("relaxed_grid_report", [](const SurfaceFace& f, const RelaxedGridParams& p) {
    RelaxedGridReport r;
    PanelMesh mesh;
    {
      py::gil_scoped_release release;
      mesh = relaxed_grid(f, p, &r);
    }
    return py::make_tuple(std::move(mesh), r);
  });
  m.def("is_valid_agent_start", &is_valid_agent_start);
  m.def("surface_evaluations", [](const SurfaceFace& f) { return f.evaluations(); });
  m.def("reset_surface_evaluations", [](const SurfaceFace& f) { f.reset_evaluations(); });
  m.def("mesh_folds", [](const PanelMesh& mesh) {
    py::array_t<long long> a({static_cast<py::ssize_t>(mesh.folds.size()), py::ssize_t(2)});
    auto r = a.mutable_unchecked<2>();
    for (std::size_t i = 0; i < mesh.folds.size(); ++i)
      r(i, 0) = mesh.folds[i][0], r(i, 1) = mesh.folds[i][1];
    return a;
  });
}
