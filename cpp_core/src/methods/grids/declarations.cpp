// Declarations of the grid methods (see tessella/methods.h).
#include "pipeline/declaration_builder.h"
#include "tessella/chebyshev_net.h"
#include "tessella/grid_methods.h"

namespace tessella::declare {

namespace {

ParamDeclaration replacing_size(ParamDeclaration d) {
  d.replaces = {"size"};
  return d;
}

MethodBuilder<IsoGridParams> iso_grid_builder() {
  MethodBuilder<IsoGridParams> b("iso_grid", "Iso-parameter grid",
                                 "uniform in (u,v), cut by the trims");
  b.param(&IsoGridParams::size,
          decl("size", ParamKind::Real, "mm", 0.0, 1e9, "Size",
               "Target panel edge length (iso_grid: counts from the mean iso-curve lengths, "
               "when UCount and VCount are 0)",
               "Panelization", "Size"))
      .param(&IsoGridParams::u_count,
             replacing_size(decl("u_count", ParamKind::Integer, "", 0, 1e6, "U count (0: use size)",
                                 "Panels across u, with VCount, instead of Size (0 = use Size; "
                                 "give either Size or the counts)",
                                 "Panelization", "UCount")))
      .param(&IsoGridParams::v_count,
             replacing_size(decl("v_count", ParamKind::Integer, "", 0, 1e6, "V count (0: use size)",
                                 "Panels across v, with UCount, instead of Size (0 = use Size; "
                                 "give either Size or the counts)",
                                 "Panelization", "VCount")));
  with_clip(b);
  return b;
}

MethodBuilder<EqualSizeGridParams> equal_size_grid_builder() {
  MethodBuilder<EqualSizeGridParams> b("equal_size_grid", "Equal-size grid",
                                       "grid lines spaced by arc length, cut by the trims");
  b.param(
      &EqualSizeGridParams::size,
      decl("size", ParamKind::Real, "mm", 0.0, 1e9, "Size",
           "Target panel edge length: grid lines spaced by arc length", "Panelization", "Size"));
  with_clip(b);
  return b;
}

// Where the net's generators cross, as a fraction of the face's u or v range.
ParamDeclaration seed_fraction(const std::string& axis) {
  return decl("seed_" + axis, ParamKind::Real, "", 0.0, 1.0, "Seed " + axis,
              "Where the net's two generators cross, as a fraction of the face's " + axis +
                  " range (0.5: the middle; unused with guides)",
              "Chebyshev net", axis == "u" ? "SeedU" : "SeedV");
}

MethodBuilder<ChebyshevNetParams> chebyshev_net_builder() {
  MethodBuilder<ChebyshevNetParams> b("chebyshev_net", "Chebyshev net (equal rods)",
                                      "every interior rod the same length (a fishnet from two "
                                      "crossing generators: iso-curves or two guide edges), cut "
                                      "by the trims");
  b.param(&ChebyshevNetParams::size,
          decl("size", ParamKind::Real, "mm", 0.0, 1e9, "Size",
               "Rod length: every rod of the net is this long, but where it meets a trim",
               "Panelization", "Size"))
      .param(&ChebyshevNetParams::seed_u, seed_fraction("u"))
      .param(&ChebyshevNetParams::seed_v, seed_fraction("v"))
      .param(&ChebyshevNetParams::guides,
             decl("guides", ParamKind::Curves, "", 0, 2, "Generator edges (optional)",
                  "Two crossing edges on or near the face for the net's generators instead of "
                  "the iso-lines through the seed (none: the iso-lines); on faces of one "
                  "surface, a guide along a cut between them follows the cut",
                  "Input", "Guides"));
  with_clip(b);
  return b;
}

}  // namespace

std::vector<MethodDeclaration> grid_methods() {
  return {iso_grid_builder().build(&iso_grid), equal_size_grid_builder().build(&equal_size_grid),
          chebyshev_net_builder().build([](const SurfaceFace& f, const ChebyshevNetParams& p) {
            return chebyshev_net(f, p);
          })};
}

}  // namespace tessella::declare

namespace tessella {

IsoGridParams iso_grid_params(const ParamValues& values) {
  check_param_values(method_declaration("iso_grid"), values);
  return declare::iso_grid_builder().filler()(values);
}

EqualSizeGridParams equal_size_grid_params(const ParamValues& values) {
  check_param_values(method_declaration("equal_size_grid"), values);
  return declare::equal_size_grid_builder().filler()(values);
}

ChebyshevNetParams chebyshev_net_params(const ParamValues& values) {
  check_param_values(method_declaration("chebyshev_net"), values);
  return declare::chebyshev_net_builder().filler()(values);
}

}  // namespace tessella
