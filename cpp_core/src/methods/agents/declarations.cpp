// Declarations of the agent methods of seed 000 (see tessella/methods.h).
#include "pipeline/declaration_builder.h"
#include "tessella/relaxed_grid.h"
#include "tessella/walking_agent.h"

namespace tessella::declare {

namespace {

const char* kGroup = "Agents";

ParamDeclaration max_deviation(const std::string& doc) {
  return decl("max_deviation", ParamKind::Real, "mm", 0.0, 1e9, "Deviation bound", doc, kGroup,
              "DeviationBound");
}
ParamDeclaration sample_step() {
  return decl("sample_step", ParamKind::Real, "", 1e-3, 0.5, "Sample step (of the span)",
              "Agents' sample step as a fraction of the parameter span (0.05 = thesis)", kGroup,
              "SampleStep");
}
ParamDeclaration start() {
  ParamDeclaration d = decl("start", ParamKind::Choice, "", 0, 0, "Start",
                            "Where the agents start: a corner of the (u,v) domain or the point "
                            "of largest curvature",
                            kGroup, "Start");
  d.choices = {"u_min_v_min", "u_max_v_min", "u_min_v_max", "u_max_v_max", "max_curvature"};
  return d;
}

MethodBuilder<WalkingAgentParams> walking_agent_builder() {
  using P = WalkingAgentParams;
  MethodBuilder<P> b("walking_agent", "Walking agent",
                     "adaptive quads with a hard deviation bound (seed 000)");
  b.param(&P::max_deviation,
          max_deviation("No panel deviates more than this from the surface (required)"))
      .param(&P::max_size,
             decl("max_size", ParamKind::Real, "mm", 0.0, 1e9, "Max panel size (0: no limit)",
                  "Longest panel edge (0 = no limit)", kGroup, "MaxSize"))
      .param(&P::diagonal_deviation, decl("diagonal_deviation", ParamKind::Real, "mm", 0.0, 1e9,
                                          "Diagonal bound (0: 2 x bound)",
                                          "Bound of the diagonal walkers (0 = 2 x DeviationBound)",
                                          kGroup, "DiagonalDeviation"))
      .param(&P::sample_step, sample_step())
      .param(&P::start, start())
      .param(&P::max_refinements,
             decl("max_refinements", ParamKind::Integer, "", 0, 1000, "Max refinements",
                  "Rounds of the hard-bound refinement", kGroup, "MaxRefinements"))
      .param(&P::edge_share,
             decl("edge_share", ParamKind::Real, "", 0.0, 1.0, "Edge share (0: try 1, 0.7, 0.5)",
                  "The agents' edge rule uses this share of DeviationBound (0 = try 1, 0.7, "
                  "0.5 and keep the fewest panels)",
                  kGroup, "EdgeShare"))
      .param(&P::iso_fallback,
             decl("iso_fallback", ParamKind::Boolean, "", 0, 1, "Iso grid fallback",
                  "Where a uniform (u,v) grid holds the bound with fewer panels than the "
                  "agents' lines (even curvature), keep the coarsest such grid",
                  kGroup, "IsoFallback"))
      .param(&P::local_lines,
             decl("local_lines", ParamKind::Boolean, "", 0, 1, "Lines stop locally",
                  "Lines stop where the surface no longer needs them: neighbouring cells merge "
                  "wherever the merged panel holds the bound (five- or six-cornered panels "
                  "where a line ends); off: the thesis' lines across the whole face",
                  kGroup, "LocalLines"));
  with_clip(b);
  return b;
}

}  // namespace

std::vector<MethodDeclaration> agent_methods() {
  std::vector<MethodDeclaration> out;
  out.push_back(walking_agent_builder().build(
      [](const SurfaceFace& f, const WalkingAgentParams& p) { return walking_agent(f, p); }));
  {
    using P = GradientDescentParams;
    MethodBuilder<P> b("gradient_descent", "Gradient descent",
                       "the walking agent's bottom-up rival (seed 000 section 5.2)");
    b.param(&P::max_deviation, max_deviation("The target deviation (required)"))
        .param(&P::sample_step, sample_step())
        .param(&P::max_step,
               decl("max_step", ParamKind::Real, "", 1e-3, 1.0, "Max step (of the span)",
                    "Longest step, fraction of the parameter span", kGroup, "MaxStep"))
        .param(&P::start, start());
    out.push_back(with_clip(b).build(&gradient_descent));
  }
  {
    using P = RelaxedGridParams;
    MethodBuilder<P> b("relaxed_grid", "Relaxed grid",
                       "fixed-topology grid relaxed to equal chord deviations (seed 000 "
                       "section 5.1)");
    b.param(&P::u_count, decl("u_count", ParamKind::Integer, "", 1, 1e6, "U count",
                              "Panels across u", "Panelization", "UCount"))
        .param(&P::v_count, decl("v_count", ParamKind::Integer, "", 1, 1e6, "V count",
                                 "Panels across v", "Panelization", "VCount"))
        .param(&P::max_iterations,
               decl("max_iterations", ParamKind::Integer, "", 0, 1e6, "Max iterations",
                    "Iteration limit", kGroup, "MaxIterations"))
        .param(&P::tolerance,
               decl("tolerance", ParamKind::Real, "", 0.0, 1.0, "Tolerance",
                    "Stop when no node moves more than this fraction of the parameter span", kGroup,
                    "Tolerance"))
        .param(&P::weight,
               decl("weight", ParamKind::Real, "", 1e-6, 1.0, "Step weight",
                    "A node moves at most this fraction of its mean rod length per iteration",
                    kGroup, "Weight"));
    out.push_back(
        with_clip(b).build([](const SurfaceFace& f, const P& p) { return relaxed_grid(f, p); }));
  }
  return out;
}

}  // namespace tessella::declare

namespace tessella {

WalkingAgentParams walking_agent_params(const ParamValues& values) {
  check_param_values(method_declaration("walking_agent"), values);
  return declare::walking_agent_builder().filler()(values);
}

}  // namespace tessella
