#pragma once
// Parsing and validation of the bonded sample + material part of a spec, and its resolved JSON
// (with defaults filled in) for the result file.
#include <string>

#include <nlohmann/json.hpp>

#include "dem/sample_spec.hpp"
#include "io/spec_reader.hpp"
#include "rupture/run.hpp"

namespace rupture::io {

/// Reads "dimension" and "sample" from the spec root.
SampleSpec parseSample(const SpecReader& root);
/// Elements the sample builder will make (packing fraction × box / mean element, less the pores).
double estimatedElements(const SampleSpec& sample);
/// Peak memory of a run on that sample, from measured bytes per element (B).
double estimatedMemoryBytes(const SampleSpec& sample);
/// The RunEstimate of a bonded scenario on that sample (field "sample.element_radius").
RunEstimate estimateBondedRun(const SampleSpec& sample);
/// Reads "material" from the spec root (dimension-independent).
MaterialSpec parseMaterial(const SpecReader& root);

nlohmann::json toJson(const SampleSpec& sample);
nlohmann::json toJson(const MaterialSpec& material);

/// The part every bonded scenario's resolved spec starts with: scenario, description (if any),
/// dimension, sample, material.
nlohmann::json bondedSpecJson(const std::string& scenario, const std::string& description,
                              const SampleSpec& sample, const MaterialSpec& material);

}  // namespace rupture::io
