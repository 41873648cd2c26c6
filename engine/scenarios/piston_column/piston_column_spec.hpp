#pragma once
// The piston-column scenario's spec: a water column in a rigid tube of diameter D and height H,
// closed by a rigid bottom and hit by a piston (prescribed speed, or a free body of mass M and
// initial speed V, as in Caleyron et al. 2013 §2). Contract: api/schemas/piston-column.schema.json, docs/sph.md.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scenarios/fluid/impactor_spec.hpp"
#include "sph/fluid_spec.hpp"
#include "sph/rigid_body.hpp"

namespace rupture {

struct PistonSpec {
  sph::BodyMotion motion = sph::BodyMotion::Free;  ///< free or prescribed
  double mass = 245.0;                             ///< kg (free; the 3D mass, see docs/sph.md for 2D)
  double speed = 5.0;                              ///< m/s into the column: initial (free) or constant (prescribed)
  sph::SpeedHistory history;                       ///< prescribed, optional: speed (m/s) against time (s)
};

struct PistonColumnSpec {
  std::string description;
  int dimension = 2;
  double diameter = 0.08;       ///< D (m)
  double columnHeight = 0.203;  ///< H (m)
  io::ResolutionSpec resolution;
  io::FluidSpec fluid;
  double soundSpeed = 1450.0;   ///< c0 resolved (m/s)
  double gravity = 9.81;        ///< m/s², along −y (2D) or −z (3D)
  PistonSpec piston;
  /// The carriage striking a piston of its own (`impactor`, 3D only; fsi/impactor_column.hpp):
  /// the piston body is then driven by the impactor column. Absent: `piston` alone.
  std::optional<fsi::ImpactorSpec> impactor;
  std::vector<std::array<double, 3>> probes;
  io::FluidRunSpec run;
  double estimatedParticles = 0;  ///< fluid and wall particles the run will hold
};

PistonColumnSpec parsePistonColumnSpec(const nlohmann::json& json);
nlohmann::json toJson(const PistonColumnSpec& spec);

}  // namespace rupture
