// Style "pmb": bond-based prototype microelastic brittle peridynamics (peridynamics/pmb.hpp) on
// square and simple-cubic lattices. Every pair within the horizon is a bond; its pairwise force is
// a central spring whose stiffness carries the micromodulus and the partial volumes (PmbLaw).
#include <cmath>
#include <numbers>
#include <sstream>

#include "bonded/bonded_system.hpp"
#include "bonded/materials/material_style.hpp"
#include "bonded/materials/with_criterion.hpp"
#include "io/physical_ranges.hpp"
#include "peridynamics/pmb.hpp"
#include "peridynamics/pmb_law.hpp"

namespace rupture {

namespace {

double ballVolume(int dimension, double r) {
  return dimension == 2 ? std::numbers::pi * r * r : 4.0 / 3.0 * std::numbers::pi * r * r * r;
}

class PmbStyle final : public MaterialStyle {
 public:
  std::string_view name() const override { return "pmb"; }
  std::vector<LatticeKind> lattices() const override { return {LatticeKind::Square, LatticeKind::SimpleCubic}; }
  // Either criterion takes its critical value from critical_stretch or from fracture_energy.
  std::vector<CriterionKey> criteria() const override {
    return {{"critical_stretch", "critical_stretch", "1"}, {"critical_energy", "fracture_energy", "J/m^2"}};
  }
  std::string criterion(const MaterialSpec& m) const override { return m.pmb.criterion; }

  void parse(const io::SpecReader& material, const MaterialContext& context, MaterialSpec& m) const override {
    const io::SpecReader block = material.object("pmb");
    PmbSpec& p = m.pmb;
    p.youngModulus = block.number("young_modulus", io::physical::modulus(), "Pa");
    p.horizonFactor = block.number("horizon_factor", io::Range::closed(1.0, 6.0), "1", p.horizonFactor);
    p.criterion = block.choice("criterion", {"critical_stretch", "critical_energy"}, "critical_stretch");
    const bool hasStretch = block.has("critical_stretch"), hasEnergy = block.has("fracture_energy");
    if (hasStretch && hasEnergy)
      block.fail("fracture_energy", "absent when critical_stretch is given (give one of the two)");
    if (hasStretch) p.criticalStretch = block.number("critical_stretch", io::Range::positive(), "1");
    if (hasEnergy) p.fractureEnergy = block.number("fracture_energy", io::Range::positive(), "J/m^2");
    if (p.criterion == "critical_energy" && hasStretch)
      block.fail("critical_stretch", "absent with criterion \"critical_energy\" (give fracture_energy, J/m^2)");
    p.compressionFactor = block.number("compression_factor", io::Range::closed(0.0, 10.0), "1", 0.0);
    if (p.compressionFactor > 0 && p.criterion != "critical_stretch")
      block.fail("compression_factor", "0 unless criterion is \"critical_stretch\"");
    p.partialVolume = block.choice("partial_volume", {"exact", "linear"}, "exact");
    block.finish();
    if (p.criterion == "critical_energy" && std::isnan(p.fractureEnergy))
      block.fail("fracture_energy", "a positive number (J/m^2), required by criterion \"critical_energy\"");
    m.contact.youngModulus = p.youngModulus;
    m.contact.poissonRatio = context.dimension == 3 ? 0.25 : 1.0 / 3.0;  // PMB's fixed ν
  }

  nlohmann::json toJson(const MaterialSpec& m) const override {
    const PmbSpec& p = m.pmb;
    nlohmann::json b = {{"young_modulus", p.youngModulus},
                        {"horizon_factor", p.horizonFactor},
                        {"criterion", p.criterion},
                        {"compression_factor", p.compressionFactor},
                        {"partial_volume", p.partialVolume}};
    if (!std::isnan(p.criticalStretch)) b["critical_stretch"] = p.criticalStretch;
    if (!std::isnan(p.fractureEnergy)) b["fracture_energy"] = p.fractureEnergy;
    return b;
  }

  /// An upper bound: half the sites whose cell can overlap the horizon ball (centres within
  /// δ + half a cell diagonal, δ = m l), ignoring the sample's faces.
  LongRangeBonds longRangeBonds(const SampleSpec& s, const MaterialSpec& m) const override {
    const LatticeKind kind = latticeKind(s.lattice);
    const double site = kind == LatticeKind::Random ? 1.0 : siteMeasure(kind);
    const double reach = m.pmb.horizonFactor + 0.5 * std::sqrt(static_cast<double>(s.dimension));
    std::ostringstream basis;
    basis << "at horizon_factor " << m.pmb.horizonFactor;
    return {0.5 * ballVolume(s.dimension, reach) / site, basis.str()};
  }

  double bondReach(const SampleSpec& s, const MaterialSpec& m) const override {
    return pmbBondReach(m.pmb, s.dimension, s.spacing, m.pmb.horizonFactor * s.spacing);
  }

  /// "exact" partial volumes keep a pair only if its cell meets the horizon.
  void pruneLatticeBonds(const SampleSpec& s, const MaterialSpec& m, BondStore& bonds) const override {
    const double l = s.spacing;
    std::vector<std::uint8_t> keep(bonds.size(), 1);
    const double delta = m.pmb.horizonFactor * l;
    for (std::size_t b = 0; b < bonds.size(); ++b) {
      const double L0 = bonds.restLength[b];
      if (L0 <= delta - 0.5 * l * std::sqrt(static_cast<double>(s.dimension))) continue;
      keep[b] = pmbPartialVolume(m.pmb, bonds.n0x[b] * L0, bonds.n0y[b] * L0, bonds.n0z[b] * L0, s.dimension, l, delta) > 0;
    }
    bonds.filter(keep);
  }

  void assign(BondedSystem& system, const SampleSpec& sample, const MaterialSpec& m) const override {
    assignPmbBonds(m.pmb, sample.dimension, sample.spacing, sample.thickness, system.particles, system.bonds);
    system.model = withCriterion(PmbLaw{}, m.pmb.criterion, m.pmb.compressionFactor);
  }

  MaterialExample example() const override {
    return {"simple-cubic",
            {{"model", "pmb"}, {"density", 2500}, {"pmb", {{"young_modulus", 70e9}, {"critical_stretch", 0.05}}}}};
  }
};

}  // namespace

const MaterialStyle& pmbStyle() {
  static const PmbStyle style;
  return style;
}

}  // namespace rupture
