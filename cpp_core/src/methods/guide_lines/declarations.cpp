// Declarations of the guide-line methods (seed 004; see tessella/methods.h).
#include "pipeline/declaration_builder.h"
#include "tessella/guide_line_diamond.h"
#include "tessella/guide_line_scaling.h"
#include "tessella/two_guide_lines.h"

namespace tessella::declare {

namespace {

const char* kGroup = "Guide lines";

ParamDeclaration guides(int count, const std::string& doc) {
  ParamDeclaration d = decl("guides", ParamKind::Curves, "", count, count,
                            count == 1 ? "Guide edge" : "Guide edges", doc, "Input", "Guides");
  d.default_value = Polylines{};
  return d;
}

template <class P>
void set_two_guides(P& p, const ParamValue& v) {
  const Polylines g = as_curves(v);
  p.guide_a = g.at(0);
  p.guide_b = g.at(1);
}

ParamDeclaration rod_length(const std::string& doc) {
  return decl("rod_length", ParamKind::Real, "mm", 0.0, 1e9, "Rod length", doc, kGroup,
              "RodLength");
}
ParamDeclaration advance(const std::string& doc) {
  return decl("advance", ParamKind::Real, "mm", 0.0, 1e9, "Advance (0: automatic)", doc, kGroup,
              "Advance");
}
ParamDeclaration guide_tolerance() {
  return decl("guide_tolerance", ParamKind::Real, "mm", 0.0, 1e12,
              "Guide tolerance (0: 5% of the model)",
              "Largest allowed distance of a guide point from the surface (0 = 5% of the "
              "model size)",
              kGroup, "GuideTolerance");
}
ParamDeclaration max_curves() {
  return decl("max_curves", ParamKind::Integer, "", 1, 1e6, "Max curves",
              "Refuse to advance more curves than this", kGroup, "MaxCurves");
}
ParamDeclaration finish_sweep() {
  return decl("finish_sweep", ParamKind::Boolean, "", 0, 1, "Finish the sweep",
              "After the paper's sweep stalls, offset the curve until it has left the face "
              "(false: the paper's sweep only)",
              kGroup, "FinishSweep");
}
ParamDeclaration ends_by_distance() {
  return decl("ends_by_distance", ParamKind::Boolean, "", 0, 1, "Ends by distance",
              "A new curve's ends are the boundary points Advance away from the curve "
              "(false: the paper's line through the advanced end point)",
              kGroup, "EndsByDistance");
}
ParamDeclaration triangulate() {
  return decl("triangulate", ParamKind::Boolean, "", 0, 1, "Triangulate",
              "Split every cell along its shorter diagonal", kGroup, "Triangulate");
}

}  // namespace

std::vector<MethodDeclaration> guide_line_methods() {
  std::vector<MethodDeclaration> out;
  {
    using P = GuideLineScalingParams;
    MethodBuilder<P> b("guide_line_scaling", "Guide line scaling (GSM)",
                       "triangular grid shell advanced from one guide curve (seed 004)");
    b.param(guides(1, "The guide curve (one edge on or near the face)"),
            [](P& p, const ParamValue& v) { p.guide = as_curves(v).at(0); })
        .param(&P::rod_length, rod_length("Target rod length L1 along the curves"))
        .param(&P::advance,
               advance("Step L between curves (0 = RodLength x sqrt(3)/2; guide_line_diamond: "
                       "0 = RodLength)"))
        .param(&P::merge_fraction,
               decl("merge_fraction", ParamKind::Real, "", 0.0, 0.999, "Merge fraction",
                    "Left-over rule: a rest chord under this fraction of the rod length is "
                    "merged into the last one",
                    kGroup, "MergeFraction"))
        .param(&P::guide_tolerance, guide_tolerance())
        .param(&P::max_curves, max_curves())
        .param(&P::finish_sweep, finish_sweep())
        .param(&P::ends_by_distance, ends_by_distance())
        .param(&P::stagger,
               decl("stagger", ParamKind::Boolean, "", 0, 1, "Staggered rows",
                    "Nodes of each curve at the feet of the neighbouring curve's rod midpoints "
                    "(false: the paper's equal chords on every curve)",
                    kGroup, "Stagger"))
        .shared("trim_deflection", &P::trim_deflection)
        .shared("max_panels", &P::max_panels)
        .partial_coverage();
    out.push_back(
        b.build([](const SurfaceFace& f, const P& p) { return guide_line_scaling(f, p); }));
  }
  {
    using P = GuideLineDiamondParams;
    MethodBuilder<P> b("guide_line_diamond", "Guide-line diamond grid",
                       "quads between two GSM curve sets (seed 004 section 5.2.1)");
    b.param(guides(2, "Two crossing guide curves (edges on or near the face)"), &set_two_guides<P>)
        .param(&P::rod_length,
               rod_length("Nominal rod length: the curves of each set are this far apart"))
        .param(&P::advance, advance("Step between the curves of each set (0 = RodLength)"))
        .param(&P::finish_sweep, finish_sweep())
        .param(&P::triangulate, triangulate())
        .param(&P::guide_tolerance, guide_tolerance())
        .param(&P::max_curves, max_curves())
        .shared("trim_deflection", &P::trim_deflection)
        .shared("max_panels", &P::max_panels)
        .partial_coverage();
    out.push_back(b.build(&guide_line_diamond));
  }
  {
    using P = TwoGuideLinesParams;
    MethodBuilder<P> b("two_guide_lines", "Two guide lines (2G2VM)",
                       "rhomboid grid from two guides through boundary vertices (seed 004 "
                       "section 6)");
    b.param(guides(2, "Two guide curves (edges on or near the face)"), &set_two_guides<P>)
        .param(&P::rod_length, rod_length("Chord of the boundary vertices"))
        .param(&P::triangulate, triangulate())
        .param(&P::boundary_divisions,
               decl("boundary_divisions", ParamKind::Integer, "", 0, 100000,
                    "Boundary divisions (0: rod length)",
                    "Divide each boundary curve into this many equal chords (0 = chords of "
                    "RodLength)",
                    kGroup, "BoundaryDivisions"))
        .param(&P::map_in_uv,
               decl("map_in_uv", ParamKind::Boolean, "", 0, 1, "Map curves in (u,v)",
                    "Move the guide through the vertex pairs in (u,v) (false: the paper's 3D "
                    "scale/rotate/project)",
                    kGroup, "MapInUV"))
        .param(&P::corner_angle,
               decl("corner_angle", ParamKind::Real, "deg", 1.0, 179.0, "Corner angle",
                    "A sharper turn of the outline splits it into boundary curves", kGroup,
                    "CornerAngle"))
        .param(&P::guide_tolerance, guide_tolerance())
        .param(&P::max_curves, max_curves())
        .shared("trim_deflection", &P::trim_deflection)
        .shared("max_panels", &P::max_panels)
        .partial_coverage();
    out.push_back(b.build([](const SurfaceFace& f, const P& p) { return two_guide_lines(f, p); }));
  }
  return out;
}

}  // namespace tessella::declare
