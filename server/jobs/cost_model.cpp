#include "jobs/cost_model.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace rupture::server {

namespace {

// Each figure is the whole wall time of the scenario's example (the form's starting spec, its
// sample and preliminary run not cached) with `rupture run --threads 1` on the project's 2-core
// development machine, shared with other work, divided by the elements and steps that the spec's
// estimate (rupture::estimateRun) gives for it, not those the run took: the ratio folds the
// estimate's own bias (a run that separates early, a particle count estimated high) into the cost.
// docs/server.md, "Preview and cost", lists the measurements and what they predict for other specs.
const std::map<std::string, CostModel>& models() {
  static const std::map<std::string, CostModel> table = {
      {"dynamic-tension",
       {2.61e-8, 0,
        "11.4 s for the 2-D example (VH at 1e6 /s, 1,631 elements, 267,312 estimated steps with its preliminary run)",
        "within about 3x: 3.3 s taken where 1.1 s was estimated (VL, no preliminary run), 4.8 s where 10.5 s was "
        "(VH at 1e7 /s); a run stops at separation, often well before its end strain, and a cached preliminary "
        "run or sample costs nothing"}},
      {"elastic-properties",
       {0, 5.63e-3, "9.2 s for the 2-D example (1,631 elements; the scenario estimates no step count)",
        "within about 3x: the loading steps depend on how the sample settles, and the cost per element grows "
        "with the coordination (3-D)"}},
      {"impact",
       {8.64e-8, 0, "7.9 s for the 2-D PMB example (16,000 particles, 338,401 bonds, 5,744 estimated steps)",
        "within about 3x for PMB at the example's horizon; the cost grows with the bonds per particle (the "
        "horizon, 3-D), and beams or lattices differ"}},
      {"dam-break",
       {1.055e-8, 0, "15.0 s for the 2-D example (82,418 estimated particles for 8,916 made, 17,256 estimated steps)",
        "within about 2x in 2-D: the step follows the flow's speed; 3-D has more neighbours per particle"}},
      {"piston-column",
       {8.59e-8, 0, "1.25 s for the 2-D example (5,221 estimated particles, 2,788 estimated steps)",
        "within about 2x: the step follows the piston's speed and the pressure wave"}},
      {"tank-impact",
       {1.033e-6, 0, "128 s for the example (29,635 estimated particles, 4,183 estimated steps)",
        "within about 3x: the plate's nodes, subcycling, contact and tearing change the cost per step"}},
  };
  return table;
}

}  // namespace

const CostModel* costModelFor(const std::string& scenario) {
  const auto it = models().find(scenario);
  return it == models().end() ? nullptr : &it->second;
}

std::optional<double> estimatedRunSeconds(const std::string& scenario, const rupture::RunEstimate& estimate,
                                          int threads) {
  const CostModel* model = costModelFor(scenario);
  if (!model || !(estimate.particles > 0)) return std::nullopt;
  const bool stepped = estimate.steps > 0 && std::isfinite(estimate.steps);
  double seconds = 0;
  if (model->secondsPerElementStep > 0 && stepped) seconds = model->secondsPerElementStep * estimate.particles * estimate.steps;
  else if (model->secondsPerElement > 0) seconds = model->secondsPerElement * estimate.particles;
  else return std::nullopt;
  return seconds / (std::max(threads, 1) * std::max(estimate.ranks, 1));
}

}  // namespace rupture::server
