// pybind11 module `freecad_workbench._core`: conversions only, no logic.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <Standard_Failure.hxx>

#include "numpy_convert.h"
#include "progress_bridge.h"
#include "tessella/errors.h"
#include "tessella/grid_methods.h"
#include "tessella/panel_mesh.h"
#include "tessella/panel_metrics.h"
#include "tessella/progress.h"
#include "tessella/shape_export.h"
#include "tessella/surface_face.h"

namespace py = pybind11;
using namespace tessella;
using bindings::rows;
using bindings::values;

void bind_analysis(py::module_& m);
void bind_boundary_driven(py::module_& m);
void bind_fabrication(py::module_& m);
void bind_pipeline(py::module_& m);

using bindings::nogil;
using bindings::with_progress;

// Areas bound in their own files (bindings/<area>.cpp).
void bind_guide_lines(py::module_& m);

PYBIND11_MODULE(_core, m) {
  m.doc() = "Tessella C++ core (see freecad_workbench.api for the user API)";
  bind_fabrication(m);
  bind_analysis(m);

  // tessella's Cancelled (a RuntimeError, so FreeCAD's recompute reports it
  // like any failed feature).
  static PyObject* cancelled_type =
      PyErr_NewException("freecad_workbench._core.Cancelled", PyExc_RuntimeError, nullptr);
  m.attr("Cancelled") = py::handle(cancelled_type);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InvalidParameter& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const InvalidGeometry& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const LimitExceeded& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const Cancelled& e) {
      PyErr_SetString(cancelled_type, e.what());
    } catch (const GeometryFailure& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    } catch (const Standard_Failure& e) {
      PyErr_SetString(PyExc_RuntimeError,
                      (std::string("geometry kernel error: ") + e.GetMessageString()).c_str());
    }
  });

  py::class_<SurfaceFace, std::shared_ptr<SurfaceFace>>(m, "SurfaceFace")
      .def_static("from_brep_string", &SurfaceFace::from_brep_string, py::arg("brep"))
      .def("bounds",
           [](const SurfaceFace& f) {
             const UvBounds b = f.bounds();
             return py::make_tuple(b.u_min, b.u_max, b.v_min, b.v_max);
           })
      .def("model_size", &SurfaceFace::model_size)
      .def("area", &SurfaceFace::area)
      .def("u_periodic", &SurfaceFace::u_periodic)
      .def("v_periodic", &SurfaceFace::v_periodic)
      .def("reversed", &SurfaceFace::reversed)
      .def("point", &SurfaceFace::point, py::arg("u"), py::arg("v"))
      .def("normal", &SurfaceFace::normal, py::arg("u"), py::arg("v"))
      .def("is_inside", &SurfaceFace::is_inside, py::arg("u"), py::arg("v"))
      .def("snap_to_trim", &SurfaceFace::snap_to_trim, py::arg("loop"), py::arg("uv"))
      .def("project",
           [](const SurfaceFace& f, const Vec3& p) {
             const Projection r = f.project(p);
             return py::make_tuple(r.uv, r.point, r.distance);
           })
      .def("trim_loops", [](const SurfaceFace& f, double deflection) {
        py::list out;
        for (const TrimLoop& loop : f.trim_loops(deflection)) {
          py::dict d;
          d["uv"] = rows<2>(loop.uv);
          d["xyz"] = rows<3>(loop.xyz);
          d["outer"] = loop.outer;
          out.append(d);
        }
        return out;
      });

  py::class_<IsoGridParams>(m, "IsoGridParams")
      .def(py::init<>())
      .def_readwrite("u_count", &IsoGridParams::u_count)
      .def_readwrite("v_count", &IsoGridParams::v_count)
      .def_readwrite("size", &IsoGridParams::size);
  py::class_<MetricsParams>(m, "MetricsParams")
      .def(py::init<>())
      .def_readwrite("samples", &MetricsParams::samples)
      .def_readwrite("threads", &MetricsParams::threads);

  py::class_<PanelMesh>(m, "PanelMesh")
      .def_property_readonly("uv", [](const PanelMesh& mesh) { return rows<2>(mesh.uv); })
      .def_property_readonly("xyz", [](const PanelMesh& mesh) { return rows<3>(mesh.xyz); })
      .def_readonly("panels", &PanelMesh::panels)
      // Each panel's corner (u,v)s (panel_corner_uv: a face set's on its own face).
      .def_property_readonly("corner_uv",
                             [](const PanelMesh& mesh) {
                               py::list out;
                               for (std::size_t p = 0; p < mesh.panels.size(); ++p)
                                 out.append(rows<2>(panel_corner_uv(mesh, p)));
                               return out;
                             })
      .def_property_readonly(
          "rods",
          [](const PanelMesh& mesh) {
            py::array_t<long long> a({static_cast<py::ssize_t>(mesh.rods.size()), py::ssize_t(2)});
            auto r = a.mutable_unchecked<2>();
            for (std::size_t i = 0; i < mesh.rods.size(); ++i)
              r(i, 0) = mesh.rods[i][0], r(i, 1) = mesh.rods[i][1];
            return a;
          })
      .def_property_readonly("nodes",
                             [](const PanelMesh& mesh) {
                               std::vector<long long> idx;
                               for (std::size_t v = 0; v < mesh.xyz.size(); ++v)
                                 if (is_node(mesh, static_cast<int>(v))) idx.push_back(v);
                               return py::array_t<long long>(static_cast<py::ssize_t>(idx.size()),
                                                             idx.data());
                             })
      .def_readonly("merged_slivers", &PanelMesh::merged_slivers)
      .def_readonly("nominal_area", &PanelMesh::nominal_area)
      .def_readonly("regular_corners", &PanelMesh::regular_corners);

  py::class_<PanelMetrics>(m, "PanelMetrics")
      .def_property_readonly("deviation", [](const PanelMetrics& x) { return values(x.deviation); })
      .def_property_readonly("deviation_unreliable",
                             [](const PanelMetrics& x) {
                               return std::vector<bool>(x.deviation_unreliable.begin(),
                                                        x.deviation_unreliable.end());
                             })
      .def_property_readonly("planarity", [](const PanelMetrics& x) { return values(x.planarity); })
      .def_property_readonly("area", [](const PanelMetrics& x) { return values(x.area); })
      .def_property_readonly("min_angle", [](const PanelMetrics& x) { return values(x.min_angle); })
      .def_property_readonly("max_angle", [](const PanelMetrics& x) { return values(x.max_angle); })
      .def_property_readonly("rod_length",
                             [](const PanelMetrics& x) { return values(x.rod_length); });

  py::class_<NodeData>(m, "NodeData")
      .def_property_readonly("valence",
                             [](const NodeData& n) {
                               return py::array_t<int>(static_cast<py::ssize_t>(n.valence.size()),
                                                       n.valence.data());
                             })
      .def_property_readonly("normal", [](const NodeData& n) { return rows<3>(n.normal); });

  m.def(
      "iso_grid",
      [](const SurfaceFace& f, const IsoGridParams& p, py::object progress) {
        return with_progress(progress, [&] { return iso_grid(f, p); });
      },
      py::arg("face"), py::arg("params"), py::arg("progress") = py::none());
  m.def(
      "measure_panels",
      [](const SurfaceFace& f, const PanelMesh& mesh, const MetricsParams& p, py::object progress) {
        return with_progress(progress, [&] { return measure_panels(f, mesh, p); });
      },
      py::arg("face"), py::arg("mesh"), py::arg("params"), py::arg("progress") = py::none());
  m.def(
      "panels_to_brep",
      [](const PanelMesh& mesh, double tol, py::object progress) {
        return with_progress(progress, [&] { return panels_to_brep(mesh, tol); });
      },
      py::arg("mesh"), py::arg("planar_tolerance"), py::arg("progress") = py::none());
  m.def(
      "panel_faces",
      [](const PanelMesh& mesh, double tol) {
        const PanelFaceList f = nogil([&] { return panel_faces(mesh, tol); });
        auto bytes = [](const std::vector<char>& v) {
          std::vector<std::uint8_t> u(v.begin(), v.end());
          return bindings::integers(u);
        };
        py::dict d;
        d["panel_offsets"] = bindings::integers(f.panel_offsets);
        d["compound"] = bytes(f.compound);
        d["corner_offsets"] = bindings::integers(f.corner_offsets);
        d["corners"] = bindings::integers(f.corners);
        d["bilinear"] = bytes(f.bilinear);
        d["origin"] = rows<3>(f.origin);
        d["normal"] = rows<3>(f.normal);
        d["tolerance"] = values(f.tolerance);
        return d;
      },
      py::arg("mesh"), py::arg("planar_tolerance"));
  m.def("rods_to_brep",
        [](const PanelMesh& mesh) { return nogil([&] { return rods_to_brep(mesh); }); });
  m.def("nodes_to_brep",
        [](const PanelMesh& mesh) { return nogil([&] { return nodes_to_brep(mesh); }); });
  bind_boundary_driven(m);
  bind_guide_lines(m);
  // The cost counter of a face and the folds of a mesh (benchmarks, tests).
  m.def("surface_evaluations", [](const SurfaceFace& f) { return f.evaluations(); });
  m.def("global_projections", [](const SurfaceFace& f) { return f.global_projections(); });
  m.def("mesh_folds", [](const PanelMesh& mesh) {
    py::array_t<long long> a({static_cast<py::ssize_t>(mesh.folds.size()), py::ssize_t(2)});
    auto r = a.mutable_unchecked<2>();
    for (std::size_t i = 0; i < mesh.folds.size(); ++i)
      r(i, 0) = mesh.folds[i][0], r(i, 1) = mesh.folds[i][1];
    return a;
  });
  bind_pipeline(m);
}
