#pragma once
// The dam-break scenario's spec: a water column of width a and height H at the back (x = 0) of a
// tank, released under gravity. Contract: api/schemas/dam-break.schema.json, docs/sph.md.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sph/fluid_spec.hpp"

namespace rupture {

struct DamBreakGeometry {
  double columnWidth = 0;            ///< a (m), along x
  double columnHeight = 0;           ///< H (m), vertical
  double tankLength = 0;             ///< m, along x
  double tankHeight = 0;             ///< m; the tank is open at the top
  std::optional<double> width;       ///< m, across (3D only; the column spans it)
};

struct DamBreakSpec {
  std::string description;
  int dimension = 2;
  DamBreakGeometry geometry;
  io::ResolutionSpec resolution;
  io::FluidSpec fluid;
  double soundSpeed = 0;             ///< c0 resolved: fluid.sound_speed or 10 √(2 g H)
  double gravity = 9.81;             ///< m/s², along −y (2D) or −z (3D)
  double estimatedParticles = 0;     ///< fluid and wall particles the run will hold
  std::vector<std::array<double, 3>> probes;
  io::FluidRunSpec run;
};

/// Throws SpecError naming the first invalid field.
DamBreakSpec parseDamBreakSpec(const nlohmann::json& json);
/// The resolved spec (defaults filled in); parses back to the same struct.
nlohmann::json toJson(const DamBreakSpec& spec);

}  // namespace rupture
