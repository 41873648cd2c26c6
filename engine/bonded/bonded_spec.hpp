#pragma once
// Parsing and validation of the bonded sample + material part of a spec, and its resolved JSON
// (with defaults filled in) for the result file.
#include <string>

#include <nlohmann/json.hpp>

#include "bonded/sample_spec.hpp"
#include "io/spec_reader.hpp"
#include "rupture/run.hpp"

namespace rupture::io {

/// Reads "dimension" and "sample" from the spec root.
SampleSpec parseSample(const SpecReader& root);
/// Elements the sample builder will make (packing fraction × box / mean element, less the pores).
double estimatedElements(const SampleSpec& sample);
/// Peak memory of a run of that material on that sample (B): measured bytes per element, plus
/// measured bytes per bond for peridynamic horizons (tens to hundreds of bonds per site).
double estimatedMemoryBytes(const SampleSpec& sample, const MaterialSpec& material);
/// The RunEstimate of a bonded scenario (field "sample.element_radius" or "sample.spacing").
RunEstimate estimateBondedRun(const SampleSpec& sample, const MaterialSpec& material);
/// The same for a scenario's spec that holds `sample` and `material` (a Scenario's estimate).
template <class Spec>
RunEstimate estimateBondedSpec(const Spec& spec) {
  return estimateBondedRun(spec.sample, spec.material);
}
/// The critical time step BondedSystem::criticalTimeStep will find on that sample (s), estimated
/// without building it: a wave's transit of the smallest element (bondedStepRule says more).
double estimatedCriticalStep(const SampleSpec& sample, const MaterialSpec& material);
/// How estimatedCriticalStep counts, for the error that quotes it.
std::string bondedStepRule();
/// Reads "material" from the spec root (dimension-independent).
MaterialSpec parseMaterial(const SpecReader& root);

/// The head every bonded scenario's spec opens with, read in this order into `spec`: "scenario"
/// (which must be `scenario`), "description", "sample" and "material".
template <class Spec>
void parseBondedHead(const SpecReader& root, const std::string& scenario, Spec& spec) {
  root.choice("scenario", {scenario});
  spec.description = root.string("description", "");
  spec.sample = parseSample(root);
  spec.material = parseMaterial(root);
}

nlohmann::json toJson(const SampleSpec& sample);
nlohmann::json toJson(const MaterialSpec& material);

/// The part every bonded scenario's resolved spec starts with: scenario, description (if any),
/// dimension, sample, material.
nlohmann::json bondedSpecJson(const std::string& scenario, const std::string& description,
                              const SampleSpec& sample, const MaterialSpec& material);

}  // namespace rupture::io
