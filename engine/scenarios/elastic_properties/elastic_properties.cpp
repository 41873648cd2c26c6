#include "scenarios/scenario_previews.hpp"
#include "scenarios/elastic_properties/elastic_properties.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <sstream>
#include <system_error>

#include "io/physical_ranges.hpp"
#include "samples/material_assignment.hpp"
#include "samples/sample_builder.hpp"
#include "bonded/materials/registry.hpp"
#include "bonded/bonded_spec.hpp"
#include "io/hdf5_file.hpp"
#include "io/spec_reader.hpp"
#include "io/result_file.hpp"
#include "scenarios/bonded/bonded_run.hpp"
#include "calibration/test_journal.hpp"
#include "scenarios/run_checkpoints.hpp"
#include "scenarios/run_support.hpp"
#include "scenarios/elastic_properties/elastic_properties_results.hpp"

namespace rupture {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr const char* kScenarioName = "elastic-properties";
/// Share of the progress bar given to building the sample (it reports no progress of its own).
constexpr double kBuildShare = 0.05;

nlohmann::json orNull(bool present, double v) { return present ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

ElasticPropertiesSpec parseElasticPropertiesSpec(const nlohmann::json& json) {
  const SpecReader root(json, "");
  ElasticPropertiesSpec s;
  io::parseBondedHead(root, kScenarioName, s);
  if (const auto target = root.optionalObject("target")) {
    // The fit varies the beams; lattice springs and PMB are mapped from E and ν directly.
    if (!materialStyle(s.material.model).calibratable())
      throw SpecError("target", "(present)",
                      "absent unless material.model is " + quotedStyleNames(&MaterialStyle::calibratable) + " (the " +
                          s.material.model + " model takes its E and nu in material." + s.material.model + ")");
    const bool young = target->has("young_modulus"), poisson = target->has("poisson_ratio");
    if (young != poisson)
      throw SpecError(young ? "target.poisson_ratio" : "target.young_modulus", "(absent)",
                      "present with target." + std::string(young ? "young_modulus" : "poisson_ratio") +
                          " (both or neither)");
    if (young) {
      ElasticTarget t;
      t.youngModulus = target->number("young_modulus", io::physical::modulus(), "Pa");
      t.poissonRatio = target->number("poisson_ratio", {-1.0, 0.5, true, true}, "1");
      s.target = t;
    }
    if (target->has("tensile_strength"))
      s.targetStrength = target->number("tensile_strength", Range::positive(), "Pa");
    else if (!young)
      throw SpecError("target", "{}", "at least target.tensile_strength, or target.young_modulus with target.poisson_ratio");
    target->finish();
  }
  if (const auto calibration = root.optionalObject("calibration")) {
    CalibrationOptions& o = s.calibration;
    o.strain = calibration->number("strain", {0.0, 0.01, true, false}, "1", o.strain);
    o.damping = calibration->number("damping", {0.0, 1.0, true, true}, "1", o.damping);
    o.tolerance = calibration->number("tolerance", {0.0, 0.1, true, false}, "1", o.tolerance);
    calibration->finish();
  }
  if (const auto run = root.optionalObject("run")) {
    s.checkpointInterval = run->number("checkpoint_interval_s", Range::closed(0.0, 1e7), "s", s.checkpointInterval);
    run->finish();
  }
  root.finish();
  return s;
}

nlohmann::json toJson(const ElasticPropertiesSpec& s) {
  nlohmann::json j = io::bondedSpecJson(kScenarioName, s.description, s.sample, s.material);
  if (s.target)
    j["target"] = {{"young_modulus", s.target->youngModulus}, {"poisson_ratio", s.target->poissonRatio}};
  if (s.targetStrength) j["target"]["tensile_strength"] = *s.targetStrength;
  j["calibration"] = {{"strain", s.calibration.strain},
                      {"damping", s.calibration.damping},
                      {"tolerance", s.calibration.tolerance}};
  j["run"] = {{"checkpoint_interval_s", s.checkpointInterval}};
  return j;
}

RunOutcome runElasticProperties(const ElasticPropertiesSpec& spec, const nlohmann::json& json, const std::string& resultPath,
                                RunControl& control) {
  auto wallStart = Clock::now();
  RunCheckpoints checkpoints(control, resultPath, kScenarioName, json, spec.checkpointInterval, wallStart);
  BondedSystem system;
  // Cancelled while building: nothing measured, the summary below reports nulls.
  const SampleReport report =
      buildRunSample(spec.sample, spec.material, system, control).value_or(SampleReport{});
  // A resumed run continues the checkpoint's copy of the file, which holds the spec.
  io::ResultFile file(resultPath, kScenarioName, checkpoints.continueFrom());
  if (!checkpoints.resuming()) file.writeSpec(toJson(spec), json);

  // The run's state is its tests' journal: the finished tests' results and the one under way,
  // polled before each relaxation step (numbered over all the run's tests; quasi-static: time 0).
  TestJournal journal({[&checkpoints](std::uint64_t step) {
                         return checkpoints.poll(step, 0.0) == RunCheckpoints::Action::Stop;
                       },
                       [&checkpoints](const TestJournal::State& part) { checkpoints.restorePart(part); }});
  checkpoints.attach(file, [&journal](StateArchive& archive) { journal.exchangeState(archive); });
  if (checkpoints.resuming()) {
    checkpoints.restore(/*partsFollow=*/true);
    if (!journal.resumesInsideATest()) checkpoints.endRestore();
  }

  auto cancelled = [&] { return control.cancel.load(std::memory_order_relaxed) || journal.stopped(); };
  CalibrationOptions options = spec.calibration;
  options.cancel = &control.cancel;
  options.journal = &journal;
  options.progress = [&control](double f) { reportProgress(control, kBuildShare + (1.0 - kBuildShare) * f); };

  // Calibratable styles (beams) measure E and ν on the way to their strength.
  const bool calibratable = materialStyle(spec.material.model).calibratable();
  bool measured = false, fitted = false;
  ElasticProperties result;
  BeamFit fit;
  if (!cancelled()) {  // a cancelled build leaves a sample not for use
    enterPhase(control, "quasi-static tests");
    reportProgress(control, kBuildShare);
    logStage(control, "sample: " + std::to_string(report.elements) + " elements, " + std::to_string(report.bonds) +
                     " bonds, porosity " + formatNumber(report.porosity));
    if (spec.target) {
      logStage(control, "fitting the beams to E = " + formatNumber(spec.target->youngModulus) + " Pa, nu = " +
                       formatNumber(spec.target->poissonRatio));
      try {
        fit = fitBeamParameters(system, spec.sample, spec.target->youngModulus, spec.target->poissonRatio, options);
      } catch (const CalibrationError& e) {
        throw SpecError("target.poisson_ratio", formatNumber(spec.target->poissonRatio),
                        std::string("a Poisson ratio the beams can reach on this sample (") + e.what() + ")");
      }
      fitted = !fit.cancelled;  // a cancelled fit's last test is not of the fitted beams: not reported
      measured = fitted;
      result = fit.achieved;
      if (fitted) assignBeams(system, spec.material, fit.beam);  // the strength below is that of the fitted beams
    } else if (calibratable) {
      measured = true;  // the strength test below measures E and ν on its way
    } else {
      logStage(control, "quasi-static tension test at strain " + formatNumber(options.strain));
      result = measureElasticProperties(system, spec.sample, options);
      measured = true;
    }
  }
  // Strength (beams): the quasi-static test, or the fit of σ_f to target.tensile_strength.
  bool strengthMeasured = false;
  StrengthResult strength;
  StrengthFit strengthFit;
  if (!cancelled() && calibratable) {
    StrengthOptions strengthOptions;
    strengthOptions.elastic = options;
    if (spec.targetStrength) {
      logStage(control, "fitting the failure stress to a tensile strength of " + formatNumber(*spec.targetStrength) + " Pa");
      try {
        strengthFit = fitFailureStress(system, spec.sample, *spec.targetStrength, strengthOptions);
      } catch (const CalibrationError& e) {
        throw SpecError("target.tensile_strength", formatNumber(*spec.targetStrength),
                        std::string("a strength the beams can reach on this sample (") + e.what() + ")");
      }
      strength = strengthFit.achieved;
    } else {
      logStage(control, "quasi-static tension to failure");
      strength = measureTensileStrength(system, spec.sample, strengthOptions);
    }
    strengthMeasured = !cancelled();
    if (!spec.target) result = strength.elastic;
  }
  const bool completed = !cancelled();
  measured = measured && completed;
  checkpoints.endRestore();  // stopped before the test under way was asked for: its part is not needed

  nlohmann::json summary = {
      {"young_modulus", orNull(measured, result.youngModulus)},
      {"poisson_ratio", orNull(measured, result.poissonRatio)},
      {"converged", result.converged && completed ? 1 : 0},
      {"relaxation_steps", static_cast<std::int64_t>(result.steps)},
      {"steps", static_cast<std::int64_t>(journal.steps())},
      {"elements", static_cast<std::int64_t>(report.elements)},
      {"bonds", static_cast<std::int64_t>(report.bonds)},
      {"mean_coordination", report.meanCoordination},
      {"porosity", report.porosity},
      {"completed", completed ? 1 : 0},
  };
  summary["tensile_strength"] = orNull(strengthMeasured, strength.tensileStrength);
  summary["crack_onset_strain"] = orNull(strengthMeasured, strength.crackOnsetStrain);
  summary["strain_at_peak"] = orNull(strengthMeasured, strength.strainAtPeak);
  if (spec.targetStrength) {
    summary["beam_failure_stress"] = orNull(strengthMeasured, strengthFit.failureStress);
    summary["target_tensile_strength"] = *spec.targetStrength;
    summary["strength_evaluations"] = strengthFit.evaluations;
  }
  if (spec.target) {
    summary["beam_young_modulus"] = orNull(fitted, fit.beam.youngModulus);
    summary["beam_radius_ratio"] = orNull(fitted, fit.beam.radiusRatio);
    summary["target_young_modulus"] = spec.target->youngModulus;
    summary["target_poisson_ratio"] = spec.target->poissonRatio;
    summary["evaluations"] = fit.evaluations;
  }
  summary["wall_time_s"] = std::chrono::duration<double>(Clock::now() - wallStart).count();
  file.writeAttributes("/summary", summary, declaredUnits<elasticPropertiesSummaryFields>());
  file.finish(completed);
  checkpoints.finished(completed);
  if (completed) reportProgress(control, 1.0);
  logStage(control, completed ? "done: E = " + formatNumber(result.youngModulus) + " Pa, nu = " + formatNumber(result.poissonRatio)
                         : "cancelled: file marked incomplete");
  return {summary, completed};
}

namespace {

/// The bonded estimate and the relaxations' time step. No step count: the relaxations end on
/// convergence or on their fixed budgets (calibration.hpp), which no spec field sets.
RunEstimate estimateElasticProperties(const ElasticPropertiesSpec& spec) {
  RunEstimate e = io::estimateBondedSpec(spec);
  e.timeStep = spec.calibration.timeStepSafety * io::estimatedCriticalStep(spec.sample, spec.material);
  e.timeStepField = "material.density";
  return e;
}

}  // namespace

Scenario elasticPropertiesScenario() {
  return withPreview(scenarioOf<ElasticPropertiesSpec>(kScenarioName, elasticPropertiesSummaryFields(), {},
                                           parseElasticPropertiesSpec, estimateElasticProperties,
                                           runElasticProperties), previewElasticProperties);
}

}  // namespace rupture
