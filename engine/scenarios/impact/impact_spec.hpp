#pragma once
// The spec of the impact scenario: a bonded 2D/3D plate (any sample and material, with notches)
// loaded by a rigid projectile, imposed velocities on boxes of particles, or tractions on boxes at
// an edge; free elsewhere. Parsed and validated once; toJson gives the resolved spec (defaults
// filled in). api/schemas/impact.schema.json describes the same fields; docs/impact.md explains them.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bonded/sample_spec.hpp"
#include "rupture/run.hpp"

namespace rupture {

struct ProjectileSpec {
  double radius = 0;                    ///< m (a sphere in 3D, a disc in the x-y plane in 2D)
  double mass = 0;                      ///< kg
  std::array<double, 3> position{};     ///< initial centre (m)
  std::array<double, 3> velocity{};     ///< initial velocity (m/s)
  double stiffness = 0;                 ///< penalty K of F = K δ² (N/m²); 0: the material's E
};

struct VelocityRegion {
  Box box;
  std::array<double, 3> velocity{};     ///< m/s
  double rampTime = 0;                  ///< linear rise from 0 over this time (s)
};

struct TractionRegion {
  Box box;
  std::array<double, 3> traction{};     ///< Pa, on the box's largest face within the sample
};

struct ImpactSpec {
  std::string description;
  SampleSpec sample;
  MaterialSpec material;
  std::optional<ProjectileSpec> projectile;
  std::vector<VelocityRegion> velocityRegions;
  std::vector<TractionRegion> tractions;
  double endTime = 0;                   ///< s
  double timeStepSafety = 0.3;          ///< dt = safety × critical step (1)
  std::optional<double> outputInterval; ///< s; default end_time / 200
  std::vector<double> snapshotTimes;    ///< s, sorted; the final state is always a snapshot
  std::int64_t maxSteps = 20'000'000;
  double checkpointInterval = 300;  ///< wall time between checkpoints (s; 0: none)
  double damageThreshold = 0.25;        ///< φ above which a particle counts as cracked (1)
  int ranks = 1;                        ///< MPI ranks asked of a server (run.ranks; docs/distributed.md)

  double interval() const { return outputInterval ? *outputInterval : endTime / 200.0; }
};

ImpactSpec parseImpactSpec(const nlohmann::json& spec);
/// The run's size (the bonded estimate) and length: run.end_time over the estimated stable step,
/// capped by run.max_steps.
RunEstimate estimateImpact(const ImpactSpec& spec);
nlohmann::json toJson(const ImpactSpec& spec);

}  // namespace rupture
