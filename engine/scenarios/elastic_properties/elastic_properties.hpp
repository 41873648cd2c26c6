#pragma once
// Scenario "elastic-properties": the beam calibration of calibration/calibration.hpp as a registered
// scenario, so that `rupture run` and rupture-server can measure (or fit) the macroscopic Young's
// modulus and Poisson ratio of a bonded sample, e.g. over a porosity sweep.
//
// One run: build the sample → either one quasi-static tension test (measureElasticProperties) or,
// with a "target", the beam fit (fitBeamParameters: up to kMaxFitEvaluations tension tests) → for
// beams, the quasi-static strength test (calibration/strength_test.hpp: tensile strength and crack-onset
// strain), or with target.tensile_strength the fit of the failure stress (fitFailureStress) → one
// HDF5 file: root attributes scenario, rupture_version, completed; /spec (json, input); /snapshots
// (empty: no particle field is written, but `rupture run` writes an XDMF sidecar over it);
// /summary with the scalars below and their "<name>_unit" attributes. Written as RESULT.part and
// renamed when closed. Cancel stops the relaxation at the next step and leaves a valid file with
// completed = 0. Checkpoints (docs/checkpoints.md) hold the tests finished so far and the one under
// way (calibration/test_journal.hpp); a resumed run replays the first and continues the second. Documentation: engine/dem/README.md; spec: api/schemas/elastic-properties.schema.json.
#include <map>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "calibration/calibration.hpp"
#include "calibration/strength_test.hpp"
#include "bonded/sample_spec.hpp"
#include "rupture/run.hpp"
#include "scenarios/scenario.hpp"

namespace rupture {

struct ElasticTarget {
  double youngModulus = 0;  ///< Pa
  double poissonRatio = 0;  ///< 1
};

struct ElasticPropertiesSpec {
  std::string description;
  SampleSpec sample;
  MaterialSpec material;
  std::optional<ElasticTarget> target;  ///< present: fit the beams to it
  std::optional<double> targetStrength; ///< target.tensile_strength (Pa): fit the beams' failure stress
  CalibrationOptions calibration;       ///< strain, damping and tolerance from the spec
  double checkpointInterval = 300;      ///< run.checkpoint_interval_s (s; 0: none)
};

/// Parses and checks a whole spec; throws SpecError naming the dotted field.
ElasticPropertiesSpec parseElasticPropertiesSpec(const nlohmann::json& json);

/// The resolved spec (defaults filled in), as written to /spec "json"; parses back to the same struct.
nlohmann::json toJson(const ElasticPropertiesSpec& spec);

/// Runs a parsed spec; `json` is the spec as given, recorded in the file.
RunOutcome runElasticProperties(const ElasticPropertiesSpec& spec, const nlohmann::json& json, const std::string& resultPath,
                                RunControl& control);


/// The registry entry (declared in scenarios/registry.cpp).
Scenario elasticPropertiesScenario();

}  // namespace rupture
