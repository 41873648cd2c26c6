// rupture calibrate SPEC.json [--target-young-modulus E --target-poisson-ratio NU] [--target-tensile-strength S]
//                             [--threads N]
//
// Prints the result as one JSON line on stdout; what it is doing goes to stderr as it happens (the
// sample's size once built, a progress bar per test or fit, the values each stage measured), since
// a calibration on the seed's sample takes minutes.
#include <omp.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <iostream>

#include "cli/cli.hpp"
#include "cli/progress_view.hpp"
#include "rupture/quantity_text.hpp"
#include "cli/spec_file.hpp"
#include "bonded/materials/registry.hpp"
#include "samples/material_assignment.hpp"
#include "calibration/calibration.hpp"
#include "calibration/strength_test.hpp"
#include "bonded/bonded_spec.hpp"

namespace rupture::cli {

int calibrateCommand(const Args& args) {
  if (args.empty())
    return usageError("calibrate: usage: rupture calibrate SPEC.json [--target-young-modulus E --target-poisson-ratio NU] "
                      "[--target-tensile-strength S] [--threads N]");
  double targetYoung = 0, targetPoisson = 0, targetStrength = 0;
  bool haveYoung = false, havePoisson = false, haveStrength = false;
  long long threads = 1;
  for (std::size_t k = 1; k < args.size(); k += 2) {
    if (k + 1 >= args.size()) return usageError("calibrate: option " + args[k] + " needs a value");
    if (args[k] == "--target-young-modulus") {
      if (!parseDoubleOption(args[k], args[k + 1], targetYoung)) return 2;
      if (!(targetYoung > 0)) return usageError("calibrate: --target-young-modulus = " + args[k + 1] + "; allowed: a number > 0 (Pa)");
      haveYoung = true;
    } else if (args[k] == "--target-poisson-ratio") {
      if (!parseDoubleOption(args[k], args[k + 1], targetPoisson)) return 2;
      if (!(targetPoisson > -1 && targetPoisson < 0.5))
        return usageError("calibrate: --target-poisson-ratio = " + args[k + 1] + "; allowed: a number in (-1, 0.5)");
      havePoisson = true;
    } else if (args[k] == "--target-tensile-strength") {
      if (!parseDoubleOption(args[k], args[k + 1], targetStrength)) return 2;
      if (!(targetStrength > 0) || !std::isfinite(targetStrength))
        return usageError("calibrate: --target-tensile-strength = " + args[k + 1] + "; allowed: a number > 0 (Pa)");
      haveStrength = true;
    } else if (args[k] == "--threads") {
      if (!parseIntOption("--threads", args[k + 1], 1, 1024, threads)) return 2;
    } else {
      return usageError("calibrate: unknown option '" + args[k] +
                        "'; allowed: --target-young-modulus, --target-poisson-ratio, --target-tensile-strength, --threads");
    }
  }
  if (haveYoung != havePoisson)
    return usageError("calibrate: give both --target-young-modulus and --target-poisson-ratio, or neither");

  nlohmann::json specJson;
  if (int code = readSpecFile(args[0], specJson)) return code;
  SampleSpec sampleSpec;
  MaterialSpec material;
  try {
    // Only the sample and material matter here; a full scenario spec is accepted as it is.
    const io::SpecReader root(specJson, "");
    sampleSpec = io::parseSample(root);
    material = io::parseMaterial(root);
  } catch (const SpecError& e) {
    return reportSpecError(args[0], e);
  }
  omp_set_num_threads(static_cast<int>(threads));
  const auto start = std::chrono::steady_clock::now();
  ProgressView view("rupture calibrate", ::isatty(STDERR_FILENO) == 1);
  view.message("building the sample");
  BondedSystem sample;
  const SampleReport report = buildSample(sampleSpec, material, sample);
  view.message(std::to_string(report.elements) + " elements, " + std::to_string(report.bonds) + " bonds, porosity " +
               formatQuantity(report.porosity, "1"));
  // The fraction a test or fit reports, drawn at most five times a second; no ETA: a relaxation
  // has no known length, so its fraction is no measure of time left.
  auto progressOf = [&view](const std::string& label) {
    return [&view, label, last = std::chrono::steady_clock::time_point{}](double fraction) mutable {
      const auto now = std::chrono::steady_clock::now();
      if (now - last < std::chrono::milliseconds(200)) return;
      last = now;
      view.update(fraction, false, label, false);
    };
  };
  auto said = [&view](const std::string& text) {
    view.close();
    view.message(text);
  };
  auto elasticText = [](const ElasticProperties& e) {
    return "E = " + formatQuantity(e.youngModulus, "Pa") + ", nu = " + formatQuantity(e.poissonRatio, "1") +
           (e.converged ? "" : " (not converged)");
  };
  nlohmann::json out;
  out["sample"] = {{"elements", report.elements},
                   {"bonds", report.bonds},
                   {"mean_coordination", report.meanCoordination},
                   {"porosity", report.porosity}};
  const bool calibratable = materialStyle(material.model).calibratable();
  if (!calibratable && (haveYoung || haveStrength))
    return usageError("calibrate: material.model = \"" + material.model + "\"; allowed: " +
                      quotedStyleNames(&MaterialStyle::calibratable) + " (the calibration fits beams)");
  try {
    if (haveYoung) {
      view.message("fitting the beams to E and nu (up to " + std::to_string(kMaxFitEvaluations) + " tension tests)");
      CalibrationOptions options;
      options.progress = progressOf("fit E, nu");
      const BeamFit fit = fitBeamParameters(sample, sampleSpec, targetYoung, targetPoisson, options);
      said("fitted in " + std::to_string(fit.evaluations) + " tests: " + elasticText(fit.achieved));
      assignBeams(sample, material, fit.beam);  // the strength below is that of the fitted beams
      out["beam"] = {{"young_modulus", fit.beam.youngModulus},
                     {"poisson_ratio", fit.beam.poissonRatio},
                     {"radius_ratio", fit.beam.radiusRatio},
                     {"failure_stress", fit.beam.failureStress}};
      out["achieved"] = {{"young_modulus", fit.achieved.youngModulus},
                         {"poisson_ratio", fit.achieved.poissonRatio},
                         {"converged", fit.achieved.converged}};
      out["target"] = {{"young_modulus", targetYoung}, {"poisson_ratio", targetPoisson}};
      out["evaluations"] = fit.evaluations;
    }
    if (haveStrength) {
      view.message("fitting the beams' failure stress to the tensile strength (up to four strength tests)");
      StrengthOptions options;
      options.elastic.progress = progressOf("fit strength");
      const StrengthFit fit = fitFailureStress(sample, sampleSpec, targetStrength, options);
      said("fitted in " + std::to_string(fit.evaluations) + " tests: tensile strength " +
           formatQuantity(fit.achieved.tensileStrength, "Pa"));
      out["beam"]["young_modulus"] = sample.beam.youngModulus;
      out["beam"]["poisson_ratio"] = sample.beam.poissonRatio;
      out["beam"]["radius_ratio"] = sample.beam.radiusRatio;
      out["beam"]["failure_stress"] = fit.failureStress;
      if (!haveYoung)
        out["achieved"] = {{"young_modulus", fit.achieved.elastic.youngModulus},
                           {"poisson_ratio", fit.achieved.elastic.poissonRatio},
                           {"converged", fit.achieved.elastic.converged}};
      out["achieved"]["tensile_strength"] = fit.achieved.tensileStrength;
      out["achieved"]["crack_onset_strain"] = fit.achieved.crackOnsetStrain;
      out["achieved"]["strain_at_peak"] = fit.achieved.strainAtPeak;
      out["target"]["tensile_strength"] = targetStrength;
      out["strength_evaluations"] = fit.evaluations;
    }
    if (!haveYoung && !haveStrength && !calibratable) {
      // Lattice and peridynamic laws: elastic properties only (their strength has its own criteria).
      view.message("measuring E and nu (quasi-static tension)");
      CalibrationOptions options;
      options.progress = progressOf("tension test");
      const ElasticProperties measured = measureElasticProperties(sample, sampleSpec, options);
      said(elasticText(measured));
      out["young_modulus"] = measured.youngModulus;
      out["poisson_ratio"] = measured.poissonRatio;
      out["converged"] = measured.converged;
      out["relaxation_steps"] = measured.steps;
    } else if (!haveYoung && !haveStrength) {
      view.message("measuring E, nu and the tensile strength (quasi-static tension to failure)");
      StrengthOptions options;
      options.elastic.progress = progressOf("tension test");
      const StrengthResult measured = measureTensileStrength(sample, sampleSpec, options);
      said(elasticText(measured.elastic) + ", tensile strength " + formatQuantity(measured.tensileStrength, "Pa") +
           ", onset strain " + formatQuantity(measured.crackOnsetStrain, "1"));
      out["young_modulus"] = measured.elastic.youngModulus;
      out["poisson_ratio"] = measured.elastic.poissonRatio;
      out["converged"] = measured.elastic.converged;
      out["tensile_strength"] = measured.tensileStrength;
      out["crack_onset_strain"] = measured.crackOnsetStrain;
      out["strain_at_peak"] = measured.strainAtPeak;
      out["relaxation_steps"] = measured.steps;
    }
  } catch (const CalibrationError& e) {
    view.close();
    return usageError(std::string("calibrate: ") + e.what());
  }
  out["wall_time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << out.dump() << std::endl;
  return 0;
}

}  // namespace rupture::cli
