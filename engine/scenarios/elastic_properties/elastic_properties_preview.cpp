// The elastic-properties preview: the sample as runElasticProperties builds it (no sample cache, as
// its run uses none); its quasi-static tests load it along each axis in turn.
#include "scenarios/scenario_previews.hpp"

#include "scenarios/bonded/bonded_preview.hpp"
#include "scenarios/bonded/sample_cache.hpp"
#include "scenarios/elastic_properties/elastic_properties.hpp"

namespace rupture {

SamplePreview previewElasticProperties(const ElasticPropertiesSpec& spec, const std::atomic<bool>& cancel,
                                       const std::string&) {
  BondedSystem system;
  SampleCacheUse use;
  const SampleReport report = buildSampleCached(spec.sample, spec.material, system, "", cancel, use);
  SamplePreview out = bondedSamplePreview(system, spec.sample, report);
  out.facts.push_back("quasi-static tension tests measure E and nu on this sample");
  return out;
}

}  // namespace rupture
