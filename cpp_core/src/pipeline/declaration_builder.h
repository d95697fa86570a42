// Private: how a method family declares its methods (see tessella/methods.h).
//
//   MethodBuilder<IsoGridParams>("iso_grid", "Iso-parameter grid", "...")
//       .param(&IsoGridParams::size, {"size", ParamKind::Real, "mm", ...})
//       .shared("trim_deflection", [](IsoGridParams& p) -> double& { return p.clip.trim_deflection;
//       }) .build(&iso_grid);
//
// A parameter is bound to the field that stores it; its default is read from
// a default-constructed params struct, so the struct stays the one source of
// the defaults.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "tessella/methods.h"

namespace tessella::declare {

// Converts a checked value to the field's type (values passed
// check_param_values, so only the alternatives it accepts arrive here).
double as_real(const ParamValue& v);
int as_integer(const ParamValue& v);
bool as_bool(const ParamValue& v);
const std::string& as_string(const ParamValue& v);
std::vector<int> as_integers(const ParamValue& v);
Polylines as_curves(const ParamValue& v);
UvPolylines as_uv_curves(const ParamValue& v);

inline ParamValue to_value(double x) { return x; }
inline ParamValue to_value(int x) { return x; }
inline ParamValue to_value(bool x) { return x; }
inline ParamValue to_value(const std::string& x) { return x; }
inline ParamValue to_value(const std::vector<int>& x) { return x; }
inline ParamValue to_value(const Polylines& x) { return x; }
inline ParamValue to_value(const UvPolylines& x) { return x; }

inline void assign(double& f, const ParamValue& v) { f = as_real(v); }
inline void assign(int& f, const ParamValue& v) { f = as_integer(v); }
inline void assign(bool& f, const ParamValue& v) { f = as_bool(v); }
inline void assign(std::string& f, const ParamValue& v) { f = as_string(v); }
inline void assign(std::vector<int>& f, const ParamValue& v) { f = as_integers(v); }
inline void assign(Polylines& f, const ParamValue& v) { f = as_curves(v); }
inline void assign(UvPolylines& f, const ParamValue& v) { f = as_uv_curves(v); }

// The shared declaration called `name` (sliver_fraction, trim_deflection, ...).
const ParamDeclaration& shared_param(const std::string& name);

template <class P>
class MethodBuilder {
 public:
  using Setter = std::function<void(P&, const ParamValue&)>;

  MethodBuilder(std::string name, std::string label, std::string doc) {
    decl_.name = std::move(name);
    decl_.label = std::move(label);
    decl_.doc = std::move(doc);
  }

  // The method's panels need not tile the face (MethodDeclaration::tiles_face).
  MethodBuilder& partial_coverage() {
    decl_.tiles_face = false;
    return *this;
  }

  // A parameter stored in a field of P (default: the field's default).
  template <class T>
  MethodBuilder& param(T P::*field, ParamDeclaration d) {
    const P defaults{};
    d.default_value = to_value(defaults.*field);
    return add(std::move(d), [field](P& p, const ParamValue& v) { assign(p.*field, v); });
  }

  // A parameter stored where `field` points (a nested member, e.g. p.clip.x).
  template <class T>
  MethodBuilder& param(T& (*field)(P&), ParamDeclaration d) {
    P defaults{};
    d.default_value = to_value(field(defaults));
    return add(std::move(d), [field](P& p, const ParamValue& v) { assign(field(p), v); });
  }

  // A parameter with its own conversion (e.g. two guides into two fields).
  MethodBuilder& param(ParamDeclaration d, Setter setter) { return add(std::move(d), setter); }

  // A shared parameter the method itself reads (stored in a field of P).
  template <class T>
  MethodBuilder& shared(const std::string& name, T P::*field) {
    ParamDeclaration d = shared_param(name);
    const P defaults{};
    d.default_value = to_value(defaults.*field);
    return add(std::move(d), [field](P& p, const ParamValue& v) { assign(p.*field, v); });
  }
  template <class T>
  MethodBuilder& shared(const std::string& name, T& (*field)(P&)) {
    ParamDeclaration d = shared_param(name);
    P defaults{};
    d.default_value = to_value(field(defaults));
    return add(std::move(d), [field](P& p, const ParamValue& v) { assign(field(p), v); });
  }

  // The params struct filled from (checked) values: what build()'s run does
  // before it calls the method (for callers of a method's other entry points).
  std::function<P(const ParamValues&)> filler() const {
    auto setters = setters_;
    return [setters](const ParamValues& values) {
      P p{};
      for (const auto& [name, set] : setters) {
        const auto it = values.find(name);
        if (it != values.end()) set(p, it->second);
      }
      return p;
    };
  }

  // The declaration, running `method` on the struct filled from the values.
  // The shared parameters the method does not read are appended (the
  // pipeline reads them).
  MethodDeclaration build(std::function<PanelMesh(const SurfaceFace&, const P&)> method) {
    for (const ParamDeclaration& s : shared_param_declarations())
      if (decl_.find(s.name) == nullptr) decl_.params.push_back(s);
    decl_.run = [fill = filler(), method](const SurfaceFace& face, const ParamValues& values) {
      return method(face, fill(values));
    };
    return decl_;
  }

 private:
  MethodBuilder& add(ParamDeclaration d, Setter setter) {
    setters_.emplace_back(d.name, std::move(setter));
    decl_.params.push_back(std::move(d));
    return *this;
  }

  MethodDeclaration decl_;
  std::vector<std::pair<std::string, Setter>> setters_;
};

// The shared parameters a grid-cut method reads into its `clip` member
// (GridClipParams: grids and agents).
template <class P>
double& clip_sliver(P& p) {
  return p.clip.sliver_fraction;
}
template <class P>
double& clip_deflection(P& p) {
  return p.clip.trim_deflection;
}
template <class P>
int& clip_max_panels(P& p) {
  return p.clip.max_panels;
}
template <class P>
MethodBuilder<P>& with_clip(MethodBuilder<P>& b) {
  return b.shared("sliver_fraction", &clip_sliver<P>)
      .shared("trim_deflection", &clip_deflection<P>)
      .shared("max_panels", &clip_max_panels<P>);
}

// Shorthand for a declaration: name, kind, unit, range, label, doc, group, property.
inline ParamDeclaration decl(std::string name, ParamKind kind, std::string unit, double minimum,
                             double maximum, std::string label, std::string doc, std::string group,
                             std::string property) {
  ParamDeclaration d;
  d.name = std::move(name);
  d.kind = kind;
  d.unit = std::move(unit);
  d.minimum = minimum;
  d.maximum = maximum;
  d.label = std::move(label);
  d.doc = std::move(doc);
  d.group = std::move(group);
  d.property = std::move(property);
  return d;
}

// The families' declarations (src/methods/<family>/declarations.cpp).
std::vector<MethodDeclaration> grid_methods();
std::vector<MethodDeclaration> boundary_driven_methods();
std::vector<MethodDeclaration> guide_line_methods();
std::vector<MethodDeclaration> agent_methods();

}  // namespace tessella::declare
