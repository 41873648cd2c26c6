#pragma once
// Each scenario's preview (Scenario::preview, rupture/sample_preview.hpp): its discretisation built
// by the functions its run starts with, stopped before the first time step. One file per scenario
// (<scenario>/<scenario>_preview.cpp); the scenario's factory attaches it with withPreview.
#include <atomic>
#include <string>

#include "rupture/sample_preview.hpp"

namespace rupture {

struct DynamicTensionSpec;
struct ElasticPropertiesSpec;
struct ImpactSpec;
struct DamBreakSpec;
struct PistonColumnSpec;
struct TankImpactSpec;

SamplePreview previewDynamicTension(const DynamicTensionSpec& spec, const std::atomic<bool>& cancel,
                                    const std::string& cacheDirectory);
SamplePreview previewElasticProperties(const ElasticPropertiesSpec& spec, const std::atomic<bool>& cancel,
                                       const std::string& cacheDirectory);
SamplePreview previewImpact(const ImpactSpec& spec, const std::atomic<bool>& cancel, const std::string& cacheDirectory);
SamplePreview previewDamBreak(const DamBreakSpec& spec, const std::atomic<bool>& cancel,
                              const std::string& cacheDirectory);
SamplePreview previewPistonColumn(const PistonColumnSpec& spec, const std::atomic<bool>& cancel,
                                  const std::string& cacheDirectory);
SamplePreview previewTankImpact(const TankImpactSpec& spec, const std::atomic<bool>& cancel,
                                const std::string& cacheDirectory);

}  // namespace rupture
