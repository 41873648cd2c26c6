#include "samples/material_assignment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bonded/bonded_system.hpp"
#include "bonded/materials/registry.hpp"
#include "bonded/sample_spec.hpp"
#include "samples/anisotropic_damage.hpp"
#include "samples/blocks.hpp"
#include "samples/bond_disorder.hpp"
#include "samples/grains.hpp"
#include "samples/inclusions.hpp"

namespace rupture {

void assignMaterial(BondedSystem& system, const SampleSpec& sample, const MaterialSpec& m, const Cancellation& cancel) {
  BondStore& bonds = system.bonds;
  materialStyle(m.model).assign(system, sample, m);
  const ParticleStore& p = system.particles;
  if (!m.interblock.empty()) {  // interblock critical stretches replace the block's s0
    const std::vector<int> block = particleBlocks(sample, p);
    for (std::size_t b = 0; b < bonds.size(); ++b) {
      const int bi = block[bonds.i[b]], bj = block[bonds.j[b]];
      if (bi == bj) continue;
      const auto forward = m.interblock.find(bi * 1000 + bj), backward = m.interblock.find(bj * 1000 + bi);
      if (forward == m.interblock.end() && backward == m.interblock.end()) continue;
      const double own = bonds.threshold[b];
      bonds.threshold[b] = std::min(forward != m.interblock.end() ? forward->second : own,
                                    backward != m.interblock.end() ? backward->second : own);
    }
  }
  std::vector<std::int32_t> grain;
  if (sample.grains.count > 0) {
    grain = voronoiGrains(sample, p, cancel);
    weakenGrainBoundaries(grain, sample.grains.boundaryFactor, bonds);
  }
  if (m.anisotropicDamage.enabled())
    assignFibres(m.anisotropicDamage, sample.dimension, materialFrames(m.anisotropicDamage, sample, p, grain), bonds);
  if (sample.inclusions.volumeFraction > 0)
    applyInclusionProperties(sample.inclusions, insideInclusions(placeInclusions(sample, cancel), system.particles),
                             system.particles, bonds);
  applyBondDisorder(m.disorder, bonds);
  for (std::size_t b = 0; b < bonds.size(); ++b)
    for (const Box& box : m.noFailureRegions) {
      const std::int32_t i = bonds.i[b], j = bonds.j[b];
      if (box.contains(p.x[i], p.y[i], p.z[i]) || box.contains(p.x[j], p.y[j], p.z[j]))
        bonds.strength[b] = std::numeric_limits<double>::infinity();
    }
  system.contact.setParameters(m.contact);
  system.bondDamping = m.localDamping;
  system.dampingWaveSpeed = m.dampingWaveSpeed;
}

void assignBeams(BondedSystem& system, const MaterialSpec& material, const BeamParameters& beams) {
  system.beam = beams;
  ContactParameters contact = system.contact.parameters();
  if (material.contactModulusFromBeams) contact.youngModulus = beamContactModulus(beams);
  if (material.contactPoissonFromBeams) contact.poissonRatio = beams.poissonRatio;
  system.contact.setParameters(contact);
  system.dampingWaveSpeed = std::sqrt(beamContactModulus(beams) / material.density);
}

}  // namespace rupture
