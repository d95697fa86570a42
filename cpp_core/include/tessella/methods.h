// THE declaration of every panelization method and its parameters: name, kind,
// unit, default, accepted range, label, tooltip, property group and the
// document property that stores it. Everything else derives from it: the
// pipeline's checks (panelize.h), the console API's checks and errors, the
// FreeCAD properties, the task panel rows and the preferences page (through
// the binding's `method_declarations()`).
//
// Adding a parameter to a method: add the field to its params struct, one
// `.param(...)` line to its declaration (src/methods/<family>/declarations.cpp),
// and use it in the method. Defaults are read from the params struct itself.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include "tessella/panel_mesh.h"
#include "tessella/vec.h"

namespace tessella {

class SurfaceFace;

using Polylines = std::vector<std::vector<Vec3>>;    // 3D curves (guides)
using UvPolylines = std::vector<std::vector<Vec2>>;  // curves in the face's (u,v)
// One parameter value. Numbers may arrive as double or int whatever the kind
// (the check converts them and refuses a fraction for an integer).
using ParamValue =
    std::variant<double, int, bool, std::string, std::vector<int>, Polylines, UvPolylines>;
// Parameters by name; a missing name keeps its default.
using ParamValues = std::map<std::string, ParamValue>;

enum class ParamKind {
  Real,         // double; unit "mm", "deg" or "" (a plain number)
  Integer,      // int (a count)
  Boolean,      // bool
  Choice,       // std::string, one of `choices`
  IntegerList,  // std::vector<int>
  Curves,       // Polylines: `minimum`..`maximum` curves (the guides)
  UvCurves,     // UvPolylines
};
const char* kind_name(ParamKind kind);  // "float", "int", "bool", "choice", "int_list", ...

struct ParamDeclaration {
  std::string name;  // the console keyword, e.g. "rod_length"
  ParamKind kind = ParamKind::Real;
  std::string unit;  // "mm", "deg" or ""
  ParamValue default_value;
  // Accepted range (Real, Integer: the value; Curves, UvCurves, IntegerList:
  // the count). The method may refuse more where it depends on the face.
  double minimum = 0.0;
  double maximum = 0.0;
  std::string label;                 // short, for the task panel
  std::string doc;                   // the tooltip and the property's documentation
  std::string group;                 // property group ("Panelization", "Guide lines", ...)
  std::string property;              // the document property that stores it ("RodLength")
  std::vector<std::string> choices;  // Choice only
  // Parameters this one replaces when it is not at its default: a document,
  // which stores every parameter, then leaves them out (iso_grid's counts
  // replace its size; the console refuses both at once).
  std::vector<std::string> replaces;
  bool shared = false;  // a pipeline parameter every method accepts
};

struct MethodDeclaration {
  std::string name;                      // "iso_grid"
  std::string label;                     // "Iso-parameter grid"
  std::string doc;                       // one sentence for the Method property and the README
  std::vector<ParamDeclaration> params;  // its own first, then the shared ones
  // Builds the method's params struct from checked values and runs it.
  std::function<PanelMesh(const SurfaceFace&, const ParamValues&)> run;
  // Whether the method's panels tile the face (no gap, no overlap): then the
  // pipeline refuses a result whose coverage is off by more than 0.1% of the
  // face (analysis/coverage.h). The guide-line methods grow curve networks
  // from their guides that stop short of some trims: their coverage is
  // measured and reported (summary coverage_warning), not yet enforced.
  bool tiles_face = true;

  const ParamDeclaration* find(const std::string& param) const;
};

// Every method, in the order the user sees them.
const std::vector<MethodDeclaration>& method_declarations();
// The method called `name`; InvalidParameter listing the known ones otherwise.
const MethodDeclaration& method_declaration(const std::string& name);
// The parameters every method accepts (sliver_fraction, min_angle, max_panels,
// trim_deflection, min_rod_length, samples): the pipeline's own.
const std::vector<ParamDeclaration>& shared_param_declarations();

// InvalidParameter unless every value names a parameter of `method`, has its
// kind and lies in its range (the message names the parameter and the range).
void check_param_values(const MethodDeclaration& method, const ParamValues& values);

}  // namespace tessella
