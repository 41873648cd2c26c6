// Styles "hookean" and "born": springs between lattice sites (core/central_spring_law.hpp,
// lattice/born_law.hpp), their constants mapped from the target E and ν by energy equivalence
// (lattice/spring_mapping.hpp). One class, two registered names: Born adds the shear spring that
// frees ν; Hookean springs fix ν to the lattice's value.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include "bonded/bonded_system.hpp"
#include "bonded/materials/material_style.hpp"
#include "bonded/materials/with_criterion.hpp"
#include "io/physical_ranges.hpp"
#include "lattice/spring_mapping.hpp"

namespace rupture {

namespace {

// The criteria springs offer and the key of each one's critical value in material.<name>.
constexpr std::array<CriterionKey, 4> kCriteria = {{{"critical_stretch", "critical_stretch", "1"},
                                                    {"critical_energy", "critical_energy", "J"},
                                                    {"stress", "failure_stress", "Pa"},
                                                    {"griffith", "fracture_energy", "J/m^2"}}};

const CriterionKey& criterionKey(const std::string& criterion) {
  for (const CriterionKey& c : kCriteria)
    if (c.name == criterion) return c;
  throw std::invalid_argument("unknown failure criterion \"" + criterion + "\"");
}

class SpringStyle final : public MaterialStyle {
 public:
  explicit SpringStyle(bool born) : m_born(born) {}

  std::string_view name() const override { return m_born ? "born" : "hookean"; }
  std::vector<LatticeKind> lattices() const override {
    return {LatticeKind::Triangular, LatticeKind::Square, LatticeKind::SimpleCubic, LatticeKind::Fcc};
  }
  std::vector<CriterionKey> criteria() const override { return {kCriteria.begin(), kCriteria.end()}; }
  std::string criterion(const MaterialSpec& m) const override { return m.springs.criterion; }

  void parse(const io::SpecReader& material, const MaterialContext& context, MaterialSpec& m) const override {
    const io::SpecReader block = material.object(std::string(name()));
    LatticeSpringSpec& sp = m.springs;
    sp.youngModulus = block.number("young_modulus", io::physical::modulus(), "Pa");
    const PoissonRange range = poissonRange(context.lattice, m_born);
    std::ostringstream allowed;
    if (range.fixed) {
      allowed << "exactly " << range.max << " (Hookean springs on the " << toString(context.lattice)
              << " lattice fix ν; use \"born\" for another value)";
      sp.poissonRatio = block.number("poisson_ratio", io::Range{-1e308, 1e308}, "1", range.max);
      if (std::fabs(sp.poissonRatio - range.max) > 1e-3) block.fail("poisson_ratio", allowed.str());
    } else {
      allowed << "(" << range.min << ", " << range.max << "] (Born springs on the " << toString(context.lattice)
              << " lattice; k_s >= 0)";
      sp.poissonRatio = block.number("poisson_ratio", io::Range{-1e308, 1e308}, "1");
      if (!(sp.poissonRatio > range.min && sp.poissonRatio <= range.max)) block.fail("poisson_ratio", allowed.str());
    }
    std::vector<std::string> names;
    for (const CriterionKey& c : kCriteria) names.emplace_back(c.name);
    sp.criterion = block.choice("criterion", names, std::string(kCriteria[0].name));
    const CriterionKey& key = criterionKey(sp.criterion);
    // Absent: unbreakable springs (elastic runs).
    sp.criticalValue = block.number(std::string(key.key), io::Range::positive(), std::string(key.unit),
                                    std::numeric_limits<double>::infinity());
    block.finish();
    m.contact.youngModulus = sp.youngModulus;
    m.contact.poissonRatio = std::clamp(sp.poissonRatio, -0.99, 0.5);
  }

  nlohmann::json toJson(const MaterialSpec& m) const override {
    const LatticeSpringSpec& sp = m.springs;
    nlohmann::json b = {{"young_modulus", sp.youngModulus}, {"poisson_ratio", sp.poissonRatio}, {"criterion", sp.criterion}};
    if (std::isfinite(sp.criticalValue)) b[std::string(criterionKey(sp.criterion).key)] = sp.criticalValue;
    return b;
  }

  double bondReach(const SampleSpec& s, const MaterialSpec&) const override {
    double longest = 0;
    for (const auto& o : springOffsets(latticeKind(s.lattice)))
      longest = std::max(longest, std::sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]));
    return longest * s.spacing * (1.0 + 1e-6);
  }

  void assign(BondedSystem& system, const SampleSpec& sample, const MaterialSpec& m) const override {
    const LatticeKind kind = latticeKind(sample.lattice);
    const LatticeSpringSpec& sp = m.springs;
    const double l = sample.spacing, t = sample.dimension == 2 ? sample.thickness : 0.0;
    const SpringConstants k = springConstants(kind, m_born, sp.youngModulus, sp.poissonRatio, l, t);
    double threshold = sp.criticalValue;  // s0 (1) or w_c (J)
    if (sp.criterion == "stress") threshold = sp.criticalValue * (sample.dimension == 2 ? l * t : l * l);  // σ_c A_b (N)
    if (sp.criterion == "griffith") threshold = sp.criticalValue / springsCutPerArea(kind, l, t);          // G_c / n_cut (J)
    BondStore& bonds = system.bonds;
    for (std::size_t b = 0; b < bonds.size(); ++b) {
      bonds.stiffness[b] = k.normalStiffness * familyStiffnessFactor(kind, bonds.restLength[b], l);
      bonds.threshold[b] = threshold;
    }
    if (m_born) system.model = withCriterion(BornLaw{k.shearRatio}, sp.criterion);
    else system.model = withCriterion(CentralSpringLaw{}, sp.criterion);
  }

  MaterialExample example() const override {
    if (m_born)
      return {"fcc",
              {{"model", "born"},
               {"density", 2500},
               {"born", {{"young_modulus", 70e9}, {"poisson_ratio", 0.2}, {"criterion", "griffith"}, {"fracture_energy", 1e6}}}}};
    return {"simple-cubic", {{"model", "hookean"}, {"density", 2500}, {"hookean", {{"young_modulus", 70e9}}}}};
  }

 private:
  bool m_born;
};

}  // namespace

const MaterialStyle& hookeanStyle() {
  static const SpringStyle style(false);
  return style;
}

const MaterialStyle& bornStyle() {
  static const SpringStyle style(true);
  return style;
}

}  // namespace rupture
