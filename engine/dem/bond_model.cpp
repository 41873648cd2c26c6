#include "dem/bond_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "dem/bonded_system.hpp"
#include "dem/grains.hpp"
#include "dem/inclusions.hpp"
#include "dem/sample_spec.hpp"
#include "lattice/lattice_geometry.hpp"
#include "lattice/spring_mapping.hpp"
#include "peridynamics/pmb.hpp"

namespace rupture {

std::string describe(const BondModel& model) {
  return std::visit(
      [](const auto& m) {
        using M = std::decay_t<decltype(m)>;
        return std::string(M::Law::kName) + "/" + M::Criterion::kName;
      },
      model);
}

namespace {

template <class Law>
BondModel withCriterion(const Law& law, const std::string& criterion, double alpha = 0.0) {
  if (criterion == "critical_stretch") return BondModelOf<Law, CriticalStretchCriterion>{law, {alpha}};
  if (criterion == "critical_energy") return BondModelOf<Law, CriticalEnergyCriterion>{law, {}};
  if (criterion == "stress") return BondModelOf<Law, StressThresholdCriterion>{law, {}};
  if (criterion == "griffith") return BondModelOf<Law, GriffithEnergyCriterion>{law, {}};
  throw std::invalid_argument("unknown failure criterion \"" + criterion + "\"");
}

void assignLatticeSprings(BondedSystem& system, const SampleSpec& sample, const MaterialSpec& m) {
  const LatticeKind kind = latticeKind(sample.lattice);
  const bool born = m.model == "born";
  const LatticeSpringSpec& sp = m.springs;
  const double l = sample.spacing, t = sample.dimension == 2 ? sample.thickness : 0.0;
  const SpringConstants k = springConstants(kind, born, sp.youngModulus, sp.poissonRatio, l, t);
  double threshold = sp.criticalValue;  // s0 (1) or w_c (J)
  if (sp.criterion == "stress") threshold = sp.criticalValue * (sample.dimension == 2 ? l * t : l * l);  // σ_c A_b (N)
  if (sp.criterion == "griffith") threshold = sp.criticalValue / springsCutPerArea(kind, l, t);          // G_c / n_cut (J)
  BondStore& bonds = system.bonds;
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    bonds.stiffness[b] = k.normalStiffness * familyStiffnessFactor(kind, bonds.restLength[b], l);
    bonds.threshold[b] = threshold;
  }
  if (born) system.model = withCriterion(BornLaw{k.shearRatio}, sp.criterion);
  else system.model = withCriterion(CentralSpringLaw{}, sp.criterion);
}

}  // namespace

void assignMaterial(BondedSystem& system, const SampleSpec& sample, const MaterialSpec& m, const Cancellation& cancel) {
  BondStore& bonds = system.bonds;
  if (m.model == "beam") {
    system.model = BeamModel{};
    system.beam = m.beam;
  } else if (m.model == "hookean" || m.model == "born") {
    assignLatticeSprings(system, sample, m);
  } else if (m.model == "pmb") {
    assignPmbBonds(m.pmb, sample.dimension, sample.spacing, sample.thickness, system.particles, bonds);
    system.model = withCriterion(CentralSpringLaw{}, m.pmb.criterion, m.pmb.compressionFactor);
  } else {
    throw std::invalid_argument("unknown material model \"" + m.model + "\"");
  }
  const ParticleStore& p = system.particles;
  if (!m.interblock.empty()) {  // interblock critical stretches replace the block's s0
    std::vector<int> block(p.size(), 1);
    for (std::size_t k = 0; k < p.size(); ++k)
      for (const BlockRegion& r : sample.blocks)
        if (r.box.contains(p.x[k], p.y[k], p.z[k])) block[k] = r.id;
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
  if (sample.grains.count > 0) weakenGrainBoundaries(voronoiGrains(sample, p, cancel), sample.grains.boundaryFactor, bonds);
  if (sample.inclusions.volumeFraction > 0)
    applyInclusionProperties(sample.inclusions, insideInclusions(placeInclusions(sample, cancel), system.particles),
                             system.particles, bonds);
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
