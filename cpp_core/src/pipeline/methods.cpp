// The method declarations of tessella/methods.h: the registry of the shared
// pipeline parameters, the families' methods, and the one check of values.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "geometry/trim_deflection.h"
#include "mesh/boundary_pieces.h"
#include "pipeline/declaration_builder.h"
#include "tessella/errors.h"
#include "tessella/grid_methods.h"
#include "tessella/panel_metrics.h"

namespace tessella {

namespace {

std::vector<ParamDeclaration> make_shared_params() {
  using declare::decl;
  const GridClipParams clip;
  const IrregularParams irregular;
  std::vector<ParamDeclaration> out;
  ParamDeclaration d;
  d = decl("sliver_fraction", ParamKind::Real, "", 0.0, 1.0, "Sliver fraction",
           "Boundary panels smaller than this fraction of a full panel are merged into a "
           "neighbour (also the area limit of an irregular panel)",
           "Panelization", "SliverFraction");
  d.default_value = clip.sliver_fraction;
  out.push_back(d);
  d = decl("min_angle", ParamKind::Real, "deg", 0.0, 180.0, "Min angle",
           "A panel with a corner angle below this is irregular", "Panelization", "MinAngle");
  d.default_value = irregular.min_angle_deg;
  out.push_back(d);
  d = decl("max_panels", ParamKind::Integer, "", 1, 1e8, "Max panels",
           "Refuse to build more panels than this", "Panelization", "MaxPanels");
  d.default_value = kDefaultMaxPanels;
  out.push_back(d);
  std::ostringstream deflection_doc;  // the one rule, geometry/trim_deflection.h
  deflection_doc << "Chord deflection of the trim polylines (0 = automatic: "
                 << kAutomaticTrimDeflection
                 << " x the model size, the diagonal of the face's bounding box)";
  d = decl("trim_deflection", ParamKind::Real, "mm", 0.0, 1e9, "Trim deflection (0: automatic)",
           deflection_doc.str(), "Advanced", "TrimDeflection");
  d.default_value = 0.0;
  out.push_back(d);
  d = decl("min_rod_length", ParamKind::Real, "mm", 0.0, 1e9, "Min rod length (0: automatic)",
           "Nodes closer than this are merged into one (a node on the trim stays exactly on "
           "it), so no rod is shorter (0 = automatic: a quarter of the nominal panel edge)",
           "Panelization", "MinRodLength");
  d.default_value = 0.0;
  out.push_back(d);
  d = decl("samples", ParamKind::Integer, "", 1, 256, "Samples",
           "Samples per panel edge for the deviation measure", "Advanced", "Samples");
  d.default_value = MetricsParams{}.samples;
  out.push_back(d);
  d = decl("boundary_deviation", ParamKind::Real, "mm", 0.0, 1e9,
           "Boundary deviation (0: automatic)",
           "A flat boundary piece whose trim edge lies farther than this from the surface gets "
           "a new node on the trim (0 = the method's deviation bound, else the largest deviation "
           "of its full panels)",
           "Panelization", "BoundaryDeviation");
  d.default_value = BoundaryPiecesParams{}.max_deviation;
  out.push_back(d);
  for (ParamDeclaration& p : out) p.shared = true;
  return out;
}

// The order every list of methods shows (task panel, property editor,
// preferences page, docs): grids, boundary-driven, the agents, then the
// guide-line methods. The preferences page stores the index in this order, so
// a new method goes at the end.
constexpr const char* kMethodOrder[] = {
    "iso_grid",           "equal_size_grid", "boundary_driven",    "walking_agent",
    "gradient_descent",   "relaxed_grid",    "guide_line_scaling", "two_guide_lines",
    "guide_line_diamond", "curvature_lines", "chebyshev_net"};

std::vector<MethodDeclaration> make_methods() {
  std::vector<MethodDeclaration> found;
  for (auto family : {declare::grid_methods, declare::boundary_driven_methods,
                      declare::guide_line_methods, declare::agent_methods})
    for (MethodDeclaration& m : family()) found.push_back(std::move(m));
  std::vector<MethodDeclaration> all;
  std::vector<char> taken(found.size(), 0);
  for (const char* name : kMethodOrder)
    for (std::size_t k = 0; k < found.size(); ++k)
      if (!taken[k] && found[k].name == name) all.push_back(std::move(found[k])), taken[k] = 1;
  // One not in the list yet (a new method): after the others.
  for (std::size_t k = 0; k < found.size(); ++k)
    if (!taken[k]) all.push_back(std::move(found[k]));
  return all;
}

std::string quoted_list(const std::vector<std::string>& names) {
  std::string s = "[";
  for (std::size_t i = 0; i < names.size(); ++i) s += (i ? ", '" : "'") + names[i] + "'";
  return s + "]";
}

[[noreturn]] void wrong_kind(const ParamDeclaration& d, const char* what) {
  throw InvalidParameter(d.name + " must be " + what);
}

double number_of(const ParamDeclaration& d, const ParamValue& v) {
  if (const double* x = std::get_if<double>(&v)) return *x;
  if (const int* x = std::get_if<int>(&v)) return *x;
  if (const bool* x = std::get_if<bool>(&v)) return *x ? 1.0 : 0.0;
  wrong_kind(d, d.kind == ParamKind::Integer ? "a whole number" : "a number");
}

std::size_t count_of(const ParamDeclaration& d, const ParamValue& v) {
  if (const auto* x = std::get_if<std::vector<int>>(&v)) {
    if (d.kind == ParamKind::IntegerList || x->empty()) return x->size();
  }
  if (d.kind == ParamKind::Curves)
    if (const auto* x = std::get_if<Polylines>(&v)) return x->size();
  if (d.kind == ParamKind::UvCurves)
    if (const auto* x = std::get_if<UvPolylines>(&v)) return x->size();
  switch (d.kind) {
    case ParamKind::IntegerList:
      wrong_kind(d, "a list of whole numbers");
    case ParamKind::Curves:
      wrong_kind(d, "a list of (N, 3) point arrays");
    default:
      wrong_kind(d, "a list of (N, 2) (u,v) point arrays");
  }
}

void check_value(const ParamDeclaration& d, const ParamValue& v) {
  switch (d.kind) {
    case ParamKind::Real:
    case ParamKind::Integer: {
      const double x = number_of(d, v);
      if (d.kind == ParamKind::Integer && std::isfinite(x) && x != std::floor(x))
        wrong_kind(d, "a whole number");
      const std::string name = d.unit.empty() ? d.name : d.name + " (" + d.unit + ")";
      require_in_range(name.c_str(), x, d.minimum, d.maximum);
      return;
    }
    case ParamKind::Boolean: {
      if (std::holds_alternative<bool>(v)) return;
      const int* x = std::get_if<int>(&v);
      if (x == nullptr || (*x != 0 && *x != 1)) wrong_kind(d, "true or false");
      return;
    }
    case ParamKind::Choice: {
      const std::string* s = std::get_if<std::string>(&v);
      if (s == nullptr || std::find(d.choices.begin(), d.choices.end(), *s) == d.choices.end())
        throw InvalidParameter(d.name + " must be one of " + quoted_list(d.choices) +
                               (s ? ", got '" + *s + "'" : std::string()));
      return;
    }
    case ParamKind::IntegerList:
    case ParamKind::Curves:
    case ParamKind::UvCurves: {
      const std::size_t n = count_of(d, v);
      if (n >= d.minimum && n <= d.maximum) return;
      std::ostringstream msg;
      const char* what = d.kind == ParamKind::IntegerList ? "value" : "curve";
      if (d.minimum == d.maximum)
        msg << d.name << " must hold exactly " << d.minimum << " " << what << "(s), got " << n;
      else
        msg << d.name << " must hold " << d.minimum << " to " << d.maximum << " " << what
            << "s, got " << n;
      throw InvalidParameter(msg.str());
    }
  }
}

}  // namespace

const char* kind_name(ParamKind kind) {
  switch (kind) {
    case ParamKind::Real:
      return "float";
    case ParamKind::Integer:
      return "int";
    case ParamKind::Boolean:
      return "bool";
    case ParamKind::Choice:
      return "choice";
    case ParamKind::IntegerList:
      return "int_list";
    case ParamKind::Curves:
      return "curves";
    case ParamKind::UvCurves:
      return "uv_curves";
  }
  return "?";
}

const ParamDeclaration* MethodDeclaration::find(const std::string& param) const {
  for (const ParamDeclaration& d : params)
    if (d.name == param) return &d;
  return nullptr;
}

const std::vector<ParamDeclaration>& shared_param_declarations() {
  static const std::vector<ParamDeclaration> shared = make_shared_params();
  return shared;
}

const std::vector<MethodDeclaration>& method_declarations() {
  static const std::vector<MethodDeclaration> methods = make_methods();
  return methods;
}

const MethodDeclaration& method_declaration(const std::string& name) {
  std::vector<std::string> names;
  for (const MethodDeclaration& m : method_declarations()) {
    if (m.name == name) return m;
    names.push_back(m.name);
  }
  std::sort(names.begin(), names.end());
  throw InvalidParameter("method must be one of " + quoted_list(names) + ", got '" + name + "'");
}

void check_param_values(const MethodDeclaration& method, const ParamValues& values) {
  std::vector<std::string> unknown;
  for (const auto& [name, value] : values)
    if (method.find(name) == nullptr) unknown.push_back(name);
  if (!unknown.empty()) {
    std::vector<std::string> accepted;
    for (const ParamDeclaration& d : method.params) accepted.push_back(d.name);
    std::sort(accepted.begin(), accepted.end());
    throw InvalidParameter("unknown parameter(s) " + quoted_list(unknown) + " for method '" +
                           method.name + "'; accepted: " + quoted_list(accepted));
  }
  for (const ParamDeclaration& d : method.params) {
    const auto it = values.find(d.name);
    if (it != values.end()) check_value(d, it->second);
  }
}

namespace declare {

const ParamDeclaration& shared_param(const std::string& name) {
  for (const ParamDeclaration& d : shared_param_declarations())
    if (d.name == name) return d;
  throw std::logic_error("no shared parameter " + name);
}

double as_real(const ParamValue& v) {
  if (const double* x = std::get_if<double>(&v)) return *x;
  if (const int* x = std::get_if<int>(&v)) return *x;
  if (const bool* x = std::get_if<bool>(&v)) return *x ? 1.0 : 0.0;
  throw InvalidParameter("a number was expected");
}
int as_integer(const ParamValue& v) { return static_cast<int>(std::llround(as_real(v))); }
bool as_bool(const ParamValue& v) {
  if (const bool* x = std::get_if<bool>(&v)) return *x;
  return as_real(v) != 0.0;
}
const std::string& as_string(const ParamValue& v) { return std::get<std::string>(v); }
std::vector<int> as_integers(const ParamValue& v) { return std::get<std::vector<int>>(v); }
Polylines as_curves(const ParamValue& v) {
  if (const auto* x = std::get_if<Polylines>(&v)) return *x;
  return {};  // an empty list arrives as an empty std::vector<int>
}
UvPolylines as_uv_curves(const ParamValue& v) {
  if (const auto* x = std::get_if<UvPolylines>(&v)) return *x;
  return {};
}

}  // namespace declare

}  // namespace tessella
