// The impact preview: the sample as runImpact builds it (no sample cache, as its run uses none),
// with the spec's driven regions and tractions as boxes and the projectile as a circle where it
// starts.
#include "scenarios/scenario_previews.hpp"

#include <algorithm>
#include <cmath>

#include "rupture/quantity_text.hpp"
#include "scenarios/bonded/bonded_preview.hpp"
#include "scenarios/bonded/sample_cache.hpp"
#include "scenarios/impact/impact_spec.hpp"

namespace rupture {

namespace {

/// The box clipped to the sample (a region may reach past it, to infinity in 2-D's z).
std::array<double, 4> clipped(const Box& box, const SampleSpec& sample) {
  auto clip = [](double v, double size) { return std::clamp(v, 0.0, size); };
  return {clip(box.min[0], sample.size[0]), clip(box.min[1], sample.size[1]), clip(box.max[0], sample.size[0]),
          clip(box.max[1], sample.size[1])};
}

std::string speedText(const std::array<double, 3>& v) {
  return formatQuantity(std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]), "m/s");
}

}  // namespace

SamplePreview previewImpact(const ImpactSpec& spec, const std::atomic<bool>& cancel, const std::string&) {
  BondedSystem system;
  SampleCacheUse use;
  const SampleReport report = buildSampleCached(spec.sample, spec.material, system, "", cancel, use);
  SamplePreview out = bondedSamplePreview(system, spec.sample, report);
  PreviewPanel& panel = out.panels.front();
  for (const VelocityRegion& r : spec.velocityRegions)
    panel.boxes.push_back({clipped(r.box, spec.sample), "driven at " + speedText(r.velocity)});
  for (const TractionRegion& r : spec.tractions)
    panel.boxes.push_back({clipped(r.box, spec.sample), "traction " + formatQuantity(std::sqrt(r.traction[0] * r.traction[0] +
                                                                                              r.traction[1] * r.traction[1] +
                                                                                              r.traction[2] * r.traction[2]),
                                                                                    "Pa")});
  if (spec.projectile)
    panel.circles.push_back({{spec.projectile->position[0], spec.projectile->position[1], spec.projectile->radius},
                             "projectile at " + speedText(spec.projectile->velocity)});
  std::string loads;
  if (!spec.velocityRegions.empty()) loads += std::to_string(spec.velocityRegions.size()) + " driven region(s)";
  if (!spec.tractions.empty()) loads += (loads.empty() ? "" : ", ") + std::to_string(spec.tractions.size()) + " traction(s)";
  if (spec.projectile) loads += (loads.empty() ? "" : ", ") + std::string("a projectile of ") +
                                formatQuantity(2 * spec.projectile->radius, "m") + " at " +
                                speedText(spec.projectile->velocity);
  if (!loads.empty()) out.facts.push_back("loaded by " + loads + " (outlined)");
  return out;
}

}  // namespace rupture
