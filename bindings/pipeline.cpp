// Bindings of the pipeline entry point and the method declarations
// (tessella/panelize.h, tessella/methods.h): conversions only.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "numpy_convert.h"
#include "progress_bridge.h"
#include "tessella/boundary_driven.h"
#include "tessella/errors.h"
#include "tessella/face_set.h"
#include "tessella/family_regularization.h"
#include "tessella/methods.h"
#include "tessella/panelize.h"
#include "tessella/planarize.h"
#include "tessella/surface_face.h"

namespace py = pybind11;
using namespace tessella;

namespace {

py::object to_python(const ParamValue& v) {
  return std::visit(
      [](const auto& x) -> py::object {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, Polylines> || std::is_same_v<T, UvPolylines>) {
          return py::list();  // curve parameters default to none
        } else {
          return py::cast(x);
        }
      },
      v);
}

py::dict declaration(const ParamDeclaration& d) {
  py::dict out;
  out["name"] = d.name;
  out["type"] = kind_name(d.kind);
  out["unit"] = d.unit;
  out["default"] = to_python(d.default_value);
  out["minimum"] = d.minimum;
  out["maximum"] = d.maximum;
  out["label"] = d.label;
  out["doc"] = d.doc;
  out["group"] = d.group;
  out["property"] = d.property;
  out["choices"] = d.choices;
  out["shared"] = d.shared;
  out["replaces"] = d.replaces;
  return out;
}

py::dict stats(const SummaryStats& s) {
  py::dict d;
  d["count"] = s.count;
  d["mean"] = s.mean;
  d["variance"] = s.variance;
  d["min"] = s.min;
  d["max"] = s.max;
  return d;
}

py::dict summary_dict(const PanelizeSummary& s) {
  py::dict d;
  d["panel_count"] = s.panel_count;
  d["rod_count"] = s.rod_count;
  d["node_count"] = s.node_count;
  d["merged_slivers"] = s.merged_slivers;
  d["merged_spikes"] = s.merged_spikes;
  d["irregular_count"] = s.irregular_count;
  d["quad_share"] = s.quad_share;
  d["nominal_area"] = s.nominal_area;
  d["face_area"] = s.face_area;
  d["model_size"] = s.model_size;
  d["fold_count"] = s.fold_count;
  d["bend_count"] = s.bend_count;
  d["split_panels"] = s.split_panels;
  d["boundary_nodes_added"] = s.boundary_nodes_added;
  d["surface_evaluations"] = s.surface_evaluations;
  d["core_seconds"] = s.core_seconds;
  d["global_projections"] = s.global_projections;
  d["metrics_seconds"] = s.metrics_seconds;
  d["metrics_threads"] = s.metrics_threads;
  d["pipeline_seconds"] = s.pipeline_seconds;
  d["panel_deviation"] = stats(s.deviation);
  d["unreliable_deviation"] = s.unreliable_deviation;
  d["panel_planarity"] = stats(s.planarity);
  d["panel_area"] = stats(s.area);
  d["rod_length"] = stats(s.rod_length);
  d["min_rod_length"] = s.min_rod_length;
  d["merged_rods"] = s.merged_rods;
  d["short_rods"] = s.short_rods;
  d["shortest_rod"] = s.shortest_rod;
  d["gap_fraction"] = s.gap_fraction;
  d["overlap_fraction"] = s.overlap_fraction;
  d["model_area_ratio"] = s.model_area_ratio;
  d["zero_area_panels"] = s.zero_area_panels;
  d["coverage_warning"] = s.coverage_warning;
  return d;
}

}  // namespace

void bind_pipeline(py::module_& m) {
  m.def(
      "method_declarations",
      [] {
        py::list out;
        for (const MethodDeclaration& method : method_declarations()) {
          py::dict d;
          d["name"] = method.name;
          d["label"] = method.label;
          d["doc"] = method.doc;
          py::list params;
          for (const ParamDeclaration& p : method.params) params.append(declaration(p));
          d["params"] = params;
          out.append(d);
        }
        return out;
      },
      "Every method with its parameters (name, type, unit, default, minimum, maximum, label, "
      "doc, group, property, choices, shared), from the C++ declarations");

  py::class_<PanelizeResult>(m, "PanelizeResult")
      .def_property_readonly(
          "face",
          [](const PanelizeResult& r) { return std::const_pointer_cast<SurfaceFace>(r.face); })
      .def_readonly("method", &PanelizeResult::method)
      .def_readonly("mesh", &PanelizeResult::mesh)
      .def_readonly("metrics", &PanelizeResult::metrics)
      .def_property_readonly("irregular",
                             [](const PanelizeResult& r) { return bindings::flags(r.irregular); })
      .def_property_readonly(
          "valence", [](const PanelizeResult& r) { return bindings::integers(r.nodes.valence); })
      .def_property_readonly(
          "normals", [](const PanelizeResult& r) { return bindings::rows<3>(r.nodes.normal); })
      .def_property_readonly("fold_angle",
                             [](const PanelizeResult& r) { return bindings::values(r.fold_angle); })
      .def_property_readonly("summary",
                             [](const PanelizeResult& r) { return summary_dict(r.summary); });

  m.def(
      "summarize", [](const std::vector<double>& v) { return stats(summarize(v)); },
      "count, mean, variance, min and max of a list of values");
  // Stage-by-stage callers (boundary_driven_stages) build the struct the same way.
  m.def("boundary_driven_params", &boundary_driven_params, py::arg("values"),
        "BoundaryDrivenParams from the declared keyword values (checked)");
  m.def(
      "panelize",
      [](std::shared_ptr<SurfaceFace> face, const std::string& method, const ParamValues& values,
         py::object progress) {
        return bindings::with_progress(progress, [&] { return panelize(face, method, values); });
      },
      py::arg("face"), py::arg("method"), py::arg("values"), py::arg("progress") = py::none(),
      "The whole pipeline (method, metrics, folds, summary) on one face");

  py::class_<FamilyRegularizationParams>(m, "FamilyRegularizationParams")
      .def(py::init<>())
      .def_readwrite("family_tolerance", &FamilyRegularizationParams::family_tolerance)
      .def_readwrite("tolerance", &FamilyRegularizationParams::tolerance)
      .def_readwrite("max_deviation", &FamilyRegularizationParams::max_deviation)
      .def_readwrite("mirror", &FamilyRegularizationParams::mirror)
      .def_readwrite("max_iterations", &FamilyRegularizationParams::max_iterations);
  py::class_<FamilyRegularizationReport>(m, "FamilyRegularizationReport")
      .def_readonly("families", &FamilyRegularizationReport::families)
      .def_readonly("families_before", &FamilyRegularizationReport::families_before)
      .def_readonly("families_after", &FamilyRegularizationReport::families_after)
      .def_readonly("max_error_before", &FamilyRegularizationReport::max_error_before)
      .def_readonly("max_error_after", &FamilyRegularizationReport::max_error_after)
      .def_readonly("max_move", &FamilyRegularizationReport::max_move)
      .def_readonly("max_node_deviation", &FamilyRegularizationReport::max_node_deviation)
      .def_readonly("moved_nodes", &FamilyRegularizationReport::moved_nodes)
      .def_readonly("iterations", &FamilyRegularizationReport::iterations);
  m.def(
      "regularize_families",
      [](const PanelizeResult& r, const FamilyRegularizationParams& p, int samples) {
        if (!r.face) throw InvalidParameter("regularize_families: give one face's result");
        FamilyRegularizationReport rep;
        PanelizeResult out =
            remeasured_result(r, regularize_families(*r.face, r.mesh, p, &rep), samples);
        return py::make_tuple(std::move(out), rep);
      },
      py::arg("result"), py::arg("params"), py::arg("samples") = 8,
      "(result with the nodes moved, report): family regularization, metrics measured again");

  py::class_<PlanarizeParams>(m, "PlanarizeParams")
      .def(py::init<>())
      .def_readwrite("planarity_tolerance", &PlanarizeParams::planarity_tolerance)
      .def_readwrite("max_deviation", &PlanarizeParams::max_deviation)
      .def_readwrite("closeness", &PlanarizeParams::closeness)
      .def_readwrite("fairness", &PlanarizeParams::fairness)
      .def_readwrite("max_iterations", &PlanarizeParams::max_iterations)
      .def_readwrite("slide_on_trims", &PlanarizeParams::slide_on_trims);
  py::class_<PlanarizeReport>(m, "PlanarizeReport")
      .def_readonly("quads", &PlanarizeReport::quads)
      .def_readonly("planar_before", &PlanarizeReport::planar_before)
      .def_readonly("planar_after", &PlanarizeReport::planar_after)
      .def_readonly("max_planarity_before", &PlanarizeReport::max_planarity_before)
      .def_readonly("max_planarity_after", &PlanarizeReport::max_planarity_after)
      .def_readonly("max_node_deviation_before", &PlanarizeReport::max_node_deviation_before)
      .def_readonly("max_node_deviation_after", &PlanarizeReport::max_node_deviation_after)
      .def_readonly("max_move", &PlanarizeReport::max_move)
      .def_readonly("iterations", &PlanarizeReport::iterations)
      .def_readonly("converged", &PlanarizeReport::converged)
      .def_readonly("sliding_nodes", &PlanarizeReport::sliding_nodes)
      .def_readonly("seconds", &PlanarizeReport::seconds);
  m.def(
      "planarize",
      [](const PanelizeResult& r, const PlanarizeParams& p, int samples, py::object progress) {
        if (!r.face) throw InvalidParameter("planarize: give one face's result");
        return bindings::with_progress(progress, [&] {
          PlanarizeReport rep;
          PanelizeResult out = remeasured_result(r, planarize(*r.face, r.mesh, p, &rep), samples);
          return std::make_pair(std::move(out), rep);
        });
      },
      py::arg("result"), py::arg("params"), py::arg("samples") = 8,
      py::arg("progress") = py::none(),
      "(result with planar quads, report): the planarization solver, metrics measured again");

  py::class_<FaceSet, std::shared_ptr<FaceSet>>(m, "FaceSet")
      .def_static(
          "from_brep_string",
          [](const std::string& brep) {
            return std::make_shared<FaceSet>(FaceSet::from_brep_string(brep));
          },
          py::arg("brep"), "Every face of a shape (BRep string), with the edges they share")
      .def("__len__", &FaceSet::size)
      .def("face",
           [](const FaceSet& s, std::size_t i) {
             if (i >= s.size()) throw py::index_error("face index out of range");
             return std::const_pointer_cast<SurfaceFace>(s.face(i));
           })
      .def_property_readonly("shared_edge_count", &FaceSet::shared_edge_count)
      .def_property_readonly("sewn", &FaceSet::sewn)
      .def_property_readonly("given_count", &FaceSet::given_count)
      .def("given_index", &FaceSet::given_index, py::arg("i"));
  py::class_<FaceSetResult>(m, "FaceSetResult")
      .def_readonly("combined", &FaceSetResult::combined)
      .def_property_readonly(
          "panel_face", [](const FaceSetResult& r) { return bindings::integers(r.panel_face); })
      .def_property_readonly(
          "vertex_face", [](const FaceSetResult& r) { return bindings::integers(r.vertex_face); })
      .def_property_readonly("rod_face",
                             [](const FaceSetResult& r) { return bindings::integers(r.rod_face); })
      .def_property_readonly("face_summaries",
                             [](const FaceSetResult& r) {
                               py::list out;
                               for (const PanelizeSummary& s : r.face_summaries)
                                 out.append(summary_dict(s));
                               return out;
                             })
      .def_readonly("shared_edges", &FaceSetResult::shared_edges)
      .def_readonly("shared_edge_nodes", &FaceSetResult::shared_edge_nodes)
      .def_readonly("shared_nodes_taken_over", &FaceSetResult::shared_nodes_taken_over)
      .def_readonly("shared_edge_segments", &FaceSetResult::shared_edge_segments)
      .def_readonly("unmatched_shared_segments", &FaceSetResult::unmatched_shared_segments)
      .def_readonly("join_warning", &FaceSetResult::join_warning)
      .def_readonly("faces_traced_across", &FaceSetResult::faces_traced_across)
      .def_readonly("faces_traced_across_surfaces", &FaceSetResult::faces_traced_across_surfaces)
      .def_readonly("smaller_size", &FaceSetResult::smaller_size)
      .def_readonly("retraced_alone", &FaceSetResult::retraced_alone)
      .def_property_readonly("skipped", [](const FaceSetResult& r) {
        py::dict out;
        for (const FaceSet::Skipped& s : r.skipped) out[py::int_(s.face)] = s.why;
        return out;
      });
  m.def(
      "panelize_faces",
      [](std::shared_ptr<FaceSet> set, const std::string& method, const ParamValues& values,
         py::object progress, int threads) {
        return bindings::with_progress(
            progress, [&] { return panelize_faces(*set, method, values, threads); });
      },
      py::arg("faces"), py::arg("method"), py::arg("values"), py::arg("progress") = py::none(),
      py::arg("threads") = 0,
      "The pipeline on every face of a FaceSet (side by side on `threads` threads), joined "
      "along the shared edges");
}
