// The dynamic-tension preview: the sample as runDynamicTension builds it (through the same sample
// cache when the spec caches its sample, so the run then reads what the form showed), with the
// loaded faces of tensionGeometry in their own colours.
#include "scenarios/scenario_previews.hpp"

#include "rupture/quantity_text.hpp"
#include "scenarios/bonded/bonded_preview.hpp"
#include "scenarios/bonded/sample_cache.hpp"
#include "scenarios/dynamic_tension/dynamic_tension_spec.hpp"
#include "scenarios/dynamic_tension/tension_loading.hpp"

namespace rupture {

SamplePreview previewDynamicTension(const DynamicTensionSpec& spec, const std::atomic<bool>& cancel,
                                    const std::string& cacheDirectory) {
  BondedSystem system;
  SampleCacheUse use;
  const SampleReport report = buildSampleCached(spec.sample, spec.material, system,
                                                spec.output.cacheSample ? cacheDirectory : "", cancel, use);
  const TensionGeometry geometry = tensionGeometry(system, spec.sample, report);
  std::vector<std::uint8_t> group(system.particles.size(), 0);
  for (std::int32_t k : geometry.xmin) group[k] = 1;
  for (std::int32_t k : geometry.xmax) group[k] = 2;
  SamplePreview out = bondedSamplePreview(system, spec.sample, report, group,
                                          {"element", "face X_min (held)", "face X_max (pulled along +x)"});
  out.fromCache = use.fromCache;
  out.facts.push_back("pulled along x at " + formatQuantity(spec.loading.strainRate, "1/s") + ", gauge length " +
                      formatQuantity(geometry.gaugeLength, "m") + "; " + std::to_string(geometry.xmin.size()) +
                      " and " + std::to_string(geometry.xmax.size()) + " face elements");
  return out;
}

}  // namespace rupture
