// buildSamplePreview: the parsed spec's scenario builds its discretisation (Scenario::preview).
#include "rupture/sample_preview.hpp"

#include "scenarios/scenario.hpp"

namespace rupture {

/// ParsedSpec's door for the preview: its scenario and its typed value.
struct SpecInternals {
  static const Scenario& scenario(const ParsedSpec& spec) { return *spec.m_scenario; }
  static const void* value(const ParsedSpec& spec) { return spec.m_value.get(); }
};

SamplePreview buildSamplePreview(const ParsedSpec& spec, const std::atomic<bool>& cancel,
                                 const std::string& cacheDirectory) {
  const Scenario& scenario = SpecInternals::scenario(spec);
  if (!scenario.preview)
    throw PreviewNotAvailable(scenario.info.name +
                              " has no single sample to show: its runs are whole published cases, each with "
                              "its own spec");
  SamplePreview preview = scenario.preview(SpecInternals::value(spec), cancel, cacheDirectory);
  preview.scenario = scenario.info.name;
  return preview;
}

}  // namespace rupture
