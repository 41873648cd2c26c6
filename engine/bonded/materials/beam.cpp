// Style "beam": cohesive Euler–Bernoulli beams between touching elements (dem/beam_law.hpp), on
// random packings or lattices. One set of beam parameters for every bond, each bond's E_μ scaled by
// its stiffness factor (1 but for inclusions and disorder; dem/beam_law.hpp), Rankine failure at the
// beam section's failure stress; the only style the calibration fits.
#include "bonded/bonded_system.hpp"
#include "bonded/materials/material_style.hpp"
#include "io/physical_ranges.hpp"

namespace rupture {

namespace {

class BeamStyle final : public MaterialStyle {
 public:
  std::string_view name() const override { return "beam"; }
  std::vector<CriterionKey> criteria() const override { return {{"rankine", "failure_stress", "Pa"}}; }
  std::string criterion(const MaterialSpec&) const override { return "rankine"; }

  void parse(const io::SpecReader& material, const MaterialContext&, MaterialSpec& m) const override {
    const io::SpecReader beam = material.object("beam");
    m.beam.youngModulus = beam.number("young_modulus", io::physical::beamModulus(), "Pa");
    m.beam.poissonRatio = beam.number("poisson_ratio", {-1.0, 0.5, true, false}, "1");
    m.beam.radiusRatio = beam.number("radius_ratio", {0.0, 1.0, true, false}, "1");
    m.beam.failureStress = beam.number("failure_stress", io::Range::positive(), "Pa");
    m.beam.bendingFromRelativeRotation =
        beam.choice("bending_stress", {"end_moment", "relative_rotation"}, "end_moment") == "relative_rotation";
    beam.finish();
    m.contact.youngModulus = beamContactModulus(m.beam);
    m.contact.poissonRatio = m.beam.poissonRatio;
    m.contactModulusFromBeams = m.contactPoissonFromBeams = true;
  }

  nlohmann::json toJson(const MaterialSpec& m) const override {
    return {{"young_modulus", m.beam.youngModulus},
            {"poisson_ratio", m.beam.poissonRatio},
            {"radius_ratio", m.beam.radiusRatio},
            {"failure_stress", m.beam.failureStress},
            {"bending_stress", m.beam.bendingFromRelativeRotation ? "relative_rotation" : "end_moment"}};
  }

  double bondReach(const SampleSpec& s, const MaterialSpec&) const override {
    return s.spacing * (1.0 + 1e-6);  // touching elements
  }

  void assign(BondedSystem& system, const SampleSpec&, const MaterialSpec& m) const override {
    system.model = BeamModel{};
    system.beam = m.beam;
  }

  bool calibratable() const override { return true; }

  MaterialExample example() const override {
    return {"simple-cubic",
            {{"model", "beam"},
             {"density", 2500},
             {"beam", {{"young_modulus", 70e9}, {"poisson_ratio", 0.25}, {"radius_ratio", 0.5}, {"failure_stress", 1e12}}}}};
  }
};

}  // namespace

const MaterialStyle& beamStyle() {
  static const BeamStyle style;
  return style;
}

}  // namespace rupture
