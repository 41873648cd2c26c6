// The tank-impact plate alone: is its time to fracture converged in the plate's node spacing?
//
// The plate of a tank-impact spec (default examples/tank-impact-TF14A5-coarse.json: the 1 mm spot face
// with its 14 mm hole in the 25 mm bottom, held at Ø 140 mm) is built exactly as the scenario
// builds it (plateGeometry, buildPlate), without the water: a uniform pressure step p is put on
// the spot face (r < D/2, where the water wets it), as a dead load along −z, and the shell runs
// alone at several plate spacings. The water's pressure is neither uniform nor constant, so the
// times are not the tank's; what the study isolates is the plate's own discretisation: whether
// the moment and place of the first fracture change when only the spacing changes. Caleyron et
// al. (2013, §5.3.1) size their elements from the delay's characteristic length
// l_car ≈ c τ_c ln(Δσ/σ_lim) and take Δl = 0.5 mm where the plate tears.
//
// Usage: plate_fracture_study [--spec FILE] [--spacings 0.002,0.0014,0.001] [--pressure Pa]
//                             [--end-time s] [--after-fracture s] [--set JSON] [--threads N]
//                             [--interval-steps N] [--spectrum N]
// --interval-steps N advances the plate by intervals of N of its stable steps (as a fluid step
// would, SphShell::advanceInterval; with --set '{"plate": {"subcycling": true}}' multi-rate)
// instead of one stable step at a time.
// --spectrum N prints the plate's largest frequencies per group of terms, bound and measured with N
// power iterations (SphShell::maxFrequency), instead of running it.
// A run stops at --end-time or --after-fracture (default 0.1 s: never) after its first fracture.
// One JSON line per spacing on stdout; docs/studies/plate_fracture.py makes the table of them
// (docs/studies/plate-fracture.md).
#include <omp.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "host_processor.hpp"
#include "shell_state_hash.hpp"
#include "scenarios/tank_impact/plate_geometry.hpp"
#include "scenarios/tank_impact/plate_observables.hpp"
#include "scenarios/tank_impact/tank_impact_spec.hpp"

#ifndef RUPTURE_SOURCE_DIR
#define RUPTURE_SOURCE_DIR "."
#endif

namespace {

struct Trial {
  double spacing = 0.0;
  std::size_t nodes = 0;
  long steps = 0;
  double timeStep = 0.0;
  double firstFracture = std::numeric_limits<double>::quiet_NaN();
  double firstFractureRadius = std::numeric_limits<double>::quiet_NaN();
  std::size_t fracturedAtEnd = 0;
  double deflectionAtFirst = std::numeric_limits<double>::quiet_NaN();  ///< at (D + d)/4, m
  double deflectionAtEnd = std::numeric_limits<double>::quiet_NaN();
  double seconds = 0.0;
  rupture::SphShell::Timings profile;  ///< the shell's wall time per pass
  std::uint64_t stateHash = 0;  ///< shellStateHash at the end
  /// Per ring of the spot face at the end: radius (m), largest damage and plastic strain (1).
  std::vector<std::array<double, 3>> rings;
};

std::vector<double> parseList(const std::string& text) {
  std::vector<double> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) values.push_back(std::atof(item.c_str()));
  return values;
}

/// --spectrum N: the plate's terms grouped by the bound's classes (g = ⌊log2(h_j / h_min)⌋, as the
/// spectral step estimate groups them), each group's largest frequency by the bound and as measured
/// with N power iterations over the terms of the group and the coarser ones (SphShell::maxFrequency);
/// one JSON line per group, for docs/shell-and-damage.md's table.
void printSpectrum(nlohmann::json specJson, double spacing, int spectrumIterations) {
  specJson["plate"]["spacing"] = spacing;
  const rupture::TankImpactSpec spec = rupture::parseTankImpactSpec(specJson);
  const rupture::PlateGeometry geometry = rupture::plateGeometry(spec.plate);
  rupture::SphShell plate = rupture::buildPlate(spec.plate, geometry);
  // The terms grouped by the bound's classes (g = ⌊log2(h_j / h_min)⌋, as the spectral estimate
  // groups them): each group's largest frequency by the bound and as measured, over the terms of
  // the group and the coarser ones (SphShell::maxFrequency).
  const std::size_t n = plate.size();
  const double C = spec.plate.shell.courantFactor;
  std::vector<int> pointGroup(n), nodeGroup(n);
  auto groupOf = [&](double h) {
    int g = 0;
    while (g < rupture::kMaxStepClass && std::ldexp(plate.stableTimeStep(), g + 1) <= h) ++g;
    return g;
  };
  for (std::size_t i = 0; i < n; ++i) {
    pointGroup[i] = groupOf(plate.pointStableStep(i));
    nodeGroup[i] = groupOf(plate.nodeStableStep(i));
  }
  for (int g = 0; g <= rupture::kMaxStepClass; ++g) {
    std::vector<std::uint8_t> pointTerm(n), nodeTerm(n);
    std::size_t points = 0;
    double finest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i) {
      pointTerm[i] = pointGroup[i] >= g;
      nodeTerm[i] = nodeGroup[i] >= g;
      if (pointGroup[i] == g) ++points;
      if (pointTerm[i]) finest = std::min(finest, plate.pointStableStep(i));
    }
    if (points == 0) continue;
    const double measured = plate.maxFrequency(pointTerm, nodeTerm, spectrumIterations);
    const double bound = 2.0 * C / finest;
    const nlohmann::json line = {{"spacing", geometry.nodes.spacing}, {"group", g}, {"points", points},
                                 {"bound_frequency", bound}, {"measured_frequency", measured},
                                 {"bound_over_measured", bound / measured}, {"critical_step", 2.0 / measured}};
    std::printf("%s\n", line.dump().c_str());
  }
}

Trial runTrial(nlohmann::json specJson, double spacing, double pressure, double endTime, double afterFracture,
               int intervalSteps) {
  specJson["plate"]["spacing"] = spacing;
  const rupture::TankImpactSpec spec = rupture::parseTankImpactSpec(specJson);
  const rupture::PlateGeometry geometry = rupture::plateGeometry(spec.plate);
  rupture::SphShell plate = rupture::buildPlate(spec.plate, geometry);
  const double faceRadius = 0.5 * spec.plate.diameter;
  const double gaugeRadius = 0.25 * (spec.plate.diameter + 2.0 * geometry.holeRadius);
  // The water wets the spot face only: a dead load −p ω_i along z on its free nodes.
  for (std::size_t i = 0; i < plate.size(); ++i) {
    const auto& x = plate.positions()[i];
    if (!plate.clamped(i) && std::hypot(x[0], x[1]) < faceRadius)
      plate.setExternalForce(i, {0.0, 0.0, -pressure * plate.integrationArea(i)});
  }
  Trial trial;
  trial.spacing = geometry.nodes.spacing;
  trial.nodes = plate.size();
  trial.timeStep = plate.stableTimeStep();
  const auto start = std::chrono::steady_clock::now();
  const std::size_t before = plate.fracturedCount();  // the hole's nodes are not created: 0
  double stopAt = endTime;
  while (plate.time() < stopAt) {
    if (intervalSteps > 0) {
      trial.steps += plate.advanceInterval(intervalSteps * trial.timeStep * (1.0 - 1e-9));
    } else {
      plate.step(trial.timeStep);
      ++trial.steps;
    }
    if (std::isnan(trial.firstFracture) && plate.fracturedCount() > before) {
      const std::size_t first = plate.fractureOrder()[before];
      trial.firstFracture = plate.fractureTime(first);
      trial.firstFractureRadius = std::hypot(geometry.nodes.x[first], geometry.nodes.y[first]);
      trial.deflectionAtFirst = rupture::deflectionAtRadius(plate, geometry, gaugeRadius);
      stopAt = std::min(endTime, trial.firstFracture + afterFracture);
    }
  }
  trial.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  trial.profile = plate.timings();
  trial.fracturedAtEnd = plate.fracturedCount() - before;
  trial.deflectionAtEnd = rupture::deflectionAtRadius(plate, geometry, gaugeRadius);
  trial.stateHash = rupture::bench::shellStateHash(plate);
  // Rings r_k = k Δ (clampedDiskNodes): the largest damage and plastic strain on each.
  for (std::size_t i = 0; i < plate.size(); ++i) {
    const double r = std::hypot(geometry.nodes.x[i], geometry.nodes.y[i]);
    if (r >= faceRadius + trial.spacing) continue;
    const std::size_t k = static_cast<std::size_t>(std::lround(r / trial.spacing));
    if (trial.rings.size() <= k) trial.rings.resize(k + 1, {0.0, 0.0, 0.0});
    trial.rings[k][0] = k * trial.spacing;
    trial.rings[k][1] = std::max(trial.rings[k][1], plate.fractured(i) ? 1.0 : plate.maxDamage(i));
    trial.rings[k][2] = std::max(trial.rings[k][2], plate.maxPlasticStrain(i));
  }
  return trial;
}

}  // namespace

int main(int argc, char** argv) {
  std::string specPath = std::string(RUPTURE_SOURCE_DIR) + "/examples/tank-impact-TF14A5-coarse.json";
  std::string spacingsText = "0.002,0.0014,0.001";
  std::string overrides;
  double pressure = 1.0e7, endTime = 2.0e-3, afterFracture = 0.1;
  int intervalSteps = 0, spectrumIterations = 0;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    const std::string value = argv[i + 1];
    if (key == "--spec") specPath = value;
    else if (key == "--spacings") spacingsText = value;
    else if (key == "--pressure") pressure = std::atof(value.c_str());
    else if (key == "--end-time") endTime = std::atof(value.c_str());
    else if (key == "--set") overrides = value;
    else if (key == "--after-fracture") afterFracture = std::atof(value.c_str());
    else if (key == "--threads") omp_set_num_threads(std::atoi(value.c_str()));
    else if (key == "--interval-steps") intervalSteps = std::atoi(value.c_str());
    else if (key == "--spectrum") spectrumIterations = std::atoi(value.c_str());
    else { std::fprintf(stderr, "unknown option %s\n", argv[i]); return 2; }
  }
  if (argc % 2 == 0) { std::fprintf(stderr, "every option takes a value\n"); return 2; }
  const std::vector<double> spacings = parseList(spacingsText);
  if (spacings.empty() || !(pressure > 0.0 && pressure < 1e9) || !(endTime > 0.0 && endTime <= 0.1) || intervalSteps < 0 || intervalSteps > 1000) {
    std::fprintf(stderr, "--spacings must list spacings (m), --pressure be in (0, 1e9) Pa, --end-time in (0, 0.1] s, --interval-steps in [0, 1000]\n");
    return 2;
  }
  nlohmann::json specJson;
  try {
    std::ifstream in(specPath);
    if (!in) { std::fprintf(stderr, "cannot read %s\n", specPath.c_str()); return 2; }
    specJson = nlohmann::json::parse(in);
    if (!overrides.empty()) specJson.merge_patch(nlohmann::json::parse(overrides));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }

  if (spectrumIterations > 0) {
    for (double spacing : spacings) printSpectrum(specJson, spacing, std::min(spectrumIterations, 1000));
    return 0;
  }
  std::vector<Trial> trials;
  for (double spacing : spacings) {
    try {
      trials.push_back(runTrial(specJson, spacing, pressure, endTime, afterFracture, intervalSteps));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "spacing %g: %s\n", spacing, e.what());
      return 2;
    }
    const Trial& t = trials.back();
    const nlohmann::json line = {
        {"spacing", t.spacing}, {"nodes", t.nodes}, {"steps", t.steps}, {"time_step", t.timeStep},
        {"first_fracture_time", std::isnan(t.firstFracture) ? nlohmann::json(nullptr) : nlohmann::json(t.firstFracture)},
        {"first_fracture_radius", std::isnan(t.firstFractureRadius) ? nlohmann::json(nullptr) : nlohmann::json(t.firstFractureRadius)},
        {"fractured_at_end", t.fracturedAtEnd},
        {"deflection_at_first_fracture", std::isnan(t.deflectionAtFirst) ? nlohmann::json(nullptr) : nlohmann::json(t.deflectionAtFirst)},
        {"deflection_at_end", t.deflectionAtEnd},
        {"rings_radius_damage_plastic_strain", t.rings}, {"seconds", t.seconds},
        {"profile_s", {{"gradients", t.profile.gradients}, {"layers", t.profile.layers}, {"forces", t.profile.forces},
                       {"integration", t.profile.integration}, {"fracture", t.profile.fracture}, {"spectrum", t.profile.spectrum}}},
        {"state_hash", t.stateHash}, {"threads", omp_get_max_threads()}, {"host", rupture::bench::hostProcessor()}};
    std::printf("%s\n", line.dump().c_str());
    std::fflush(stdout);
  }

  return 0;
}
