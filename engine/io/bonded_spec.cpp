#include "io/bonded_spec.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace rupture::io {

namespace {
// Guard against specs that would build an absurd number of elements (and exhaust memory).
constexpr double kMaxElements = 5e6;
// Pores are placed one by one (random sequential addition, engine/dem/sample_builder.cpp): bound
// their number so placement and carving stay seconds, and the porosity below the jamming limit of
// random sequential addition (0.547 for equal disks, 0.382 for equal spheres) with a margin for
// the finite box, where pore centres stay one radius away from the walls.
constexpr double kMaxPores = 1e4;
constexpr double kMaxPorosity2D = 0.5;
constexpr double kMaxPorosity3D = 0.35;

std::string shortNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

double ballVolume(int dimension, double r) {
  return dimension == 2 ? std::numbers::pi * r * r : 4.0 / 3.0 * std::numbers::pi * r * r * r;
}

/// Mean of r^d for r uniform in [a, b] (the mean element or pore area/volume over π or 4π/3).
double meanPower(int dimension, double a, double b) {
  if (b - a <= 1e-15 * b) return std::pow(b, dimension);
  return (std::pow(b, dimension + 1) - std::pow(a, dimension + 1)) / ((dimension + 1) * (b - a));
}
}  // namespace

double estimatedElements(const SampleSpec& s) {
  double volume = 1;
  for (int a = 0; a < s.dimension; ++a) volume *= s.size[a];
  const double meanElement = (s.dimension == 2 ? std::numbers::pi : 4.0 / 3.0 * std::numbers::pi) *
                             meanPower(s.dimension, s.elementRadius * (1 - s.radiusDispersion),
                                       s.elementRadius * (1 + s.radiusDispersion));
  const double fraction = s.dimension == 2 ? 0.84 : 0.58;  // the packing's target solid fraction
  return fraction * volume / meanElement * (1.0 - s.porosity);
}

double estimatedMemoryBytes(const SampleSpec& s) {
  // Peak resident memory of dynamic-tension runs divided by their elements (particle and bond
  // arrays, contact lists, snapshots in flight), measured at 86k elements in 2D (0.85 kB) and 52k
  // in 3D (1.15 kB), rounded up.
  return estimatedElements(s) * (s.dimension == 2 ? 1.0e3 : 1.5e3);
}

RunEstimate estimateBondedRun(const SampleSpec& sample) {
  return {estimatedElements(sample), estimatedMemoryBytes(sample), "sample.element_radius"};
}

SampleSpec parseSample(const SpecReader& root) {
  SampleSpec s;
  s.dimension = static_cast<int>(root.integer("dimension", 2, 3));
  const SpecReader sample = root.object("sample");
  const std::size_t d = static_cast<std::size_t>(s.dimension);
  const auto size = sample.numbers("size", d, d, Range::positive(), "m");
  for (std::size_t a = 0; a < d; ++a) s.size[a] = size[a];
  s.elementRadius = sample.number("element_radius", Range::positive(), "m");
  s.radiusDispersion = sample.number("radius_dispersion", Range::closed(0.0, 0.5), "1", s.radiusDispersion);
  const double maxPorosity = s.dimension == 2 ? kMaxPorosity2D : kMaxPorosity3D;
  s.porosity = sample.number("porosity", Range::closed(0.0, maxPorosity), "1", 0.0);
  if (s.porosity > 0 || sample.has("pore_radius")) {
    const auto pores = sample.numbers("pore_radius", 2, 2, Range::positive(), "m");
    if (pores[0] > pores[1]) sample.fail("pore_radius", "[min, max] with min <= max (m)");
    s.poreRadius = {pores[0], pores[1]};
    const double smallestEdge = *std::min_element(size.begin(), size.end());
    if (2.0 * pores[1] >= smallestEdge)
      sample.fail("pore_radius", "pore diameters smaller than the smallest sample edge");
    // A pore is carved out of whole elements: one smaller than an element carves nothing.
    if (pores[0] < s.elementRadius)
      sample.fail("pore_radius", "pore radii >= sample.element_radius (" + shortNumber(s.elementRadius) + " m)");
  }
  s.seed = static_cast<std::uint64_t>(sample.integer("seed", 0, (std::int64_t{1} << 53), 1));
  s.bondGap = sample.number("bond_gap", Range::closed(0.0, 1.0), "1", s.bondGap);
  sample.finish();

  double volume = 1;
  for (std::size_t a = 0; a < d; ++a) volume *= s.size[a];
  const double estimate = volume / ballVolume(s.dimension, s.elementRadius);
  if (estimate > kMaxElements)
    throw SpecError(sample.pathOf("element_radius"), shortNumber(s.elementRadius),
                    "a radius giving at most 5e6 elements for this sample.size (this gives about " +
                        shortNumber(std::round(estimate)) + ")");
  if (estimate < 8)
    throw SpecError(sample.pathOf("element_radius"), shortNumber(s.elementRadius),
                    "a radius small enough for at least 8 elements in sample.size");
  if (s.porosity > 0) {
    const double pores = s.porosity * volume /
                         ((s.dimension == 2 ? std::numbers::pi : 4.0 / 3.0 * std::numbers::pi) *
                          meanPower(s.dimension, s.poreRadius[0], s.poreRadius[1]));
    if (pores > kMaxPores)
      throw SpecError(sample.pathOf("pore_radius"), "[" + shortNumber(s.poreRadius[0]) + ", " + shortNumber(s.poreRadius[1]) + "]",
                      "pore radii large enough for at most 10000 pores at this porosity and sample.size (these need about " +
                          shortNumber(std::round(pores)) + ")");
  }
  return s;
}

MaterialSpec parseMaterial(const SpecReader& root) {
  MaterialSpec m;
  const SpecReader material = root.object("material");
  m.model = material.choice("model", {"beam"});
  m.density = material.number("density", Range::positive(), "kg/m^3");
  const SpecReader beam = material.object("beam");
  m.beam.youngModulus = beam.number("young_modulus", Range::positive(), "Pa");
  m.beam.poissonRatio = beam.number("poisson_ratio", {-1.0, 0.5, true, false}, "1");
  m.beam.radiusRatio = beam.number("radius_ratio", {0.0, 1.0, true, false}, "1");
  m.beam.failureStress = beam.number("failure_stress", Range::positive(), "Pa");
  beam.finish();
  // Default contact modulus ~ the macroscopic modulus the beams give (E_M ∝ E_μ r_μ², see
  // physics-reference §1.6; on our 2D packings E_M ≈ 0.9 E_μ ratio²), not the fictitious E_μ.
  m.contact.youngModulus = m.beam.youngModulus * m.beam.radiusRatio * m.beam.radiusRatio;
  m.contact.poissonRatio = m.beam.poissonRatio;
  if (auto contact = material.optionalObject("contact")) {
    m.contact.enabled = contact->boolean("enabled", true);
    m.contact.youngModulus = contact->number("young_modulus", Range::positive(), "Pa", m.contact.youngModulus);
    m.contact.poissonRatio = contact->number("poisson_ratio", {-1.0, 0.5, true, true}, "1", m.contact.poissonRatio);
    m.contact.friction = contact->number("friction", Range::closed(0.0, 2.0), "1", m.contact.friction);
    m.contact.dampingRatio = contact->number("damping_ratio", Range::closed(0.0, 1.0), "1", m.contact.dampingRatio);
    contact->finish();
  }
  material.finish();
  return m;
}

nlohmann::json toJson(const SampleSpec& s) {
  nlohmann::json size = nlohmann::json::array();
  for (int a = 0; a < s.dimension; ++a) size.push_back(s.size[a]);
  nlohmann::json j = {{"size", size},
                      {"element_radius", s.elementRadius},
                      {"radius_dispersion", s.radiusDispersion},
                      {"porosity", s.porosity},
                      {"seed", s.seed},
                      {"bond_gap", s.bondGap}};
  if (s.porosity > 0) j["pore_radius"] = {s.poreRadius[0], s.poreRadius[1]};
  return j;
}

nlohmann::json toJson(const MaterialSpec& m) {
  return {{"model", m.model},
          {"density", m.density},
          {"beam",
           {{"young_modulus", m.beam.youngModulus},
            {"poisson_ratio", m.beam.poissonRatio},
            {"radius_ratio", m.beam.radiusRatio},
            {"failure_stress", m.beam.failureStress}}},
          {"contact",
           {{"enabled", m.contact.enabled},
            {"young_modulus", m.contact.youngModulus},
            {"poisson_ratio", m.contact.poissonRatio},
            {"friction", m.contact.friction},
            {"damping_ratio", m.contact.dampingRatio}}}};
}

nlohmann::json bondedSpecJson(const std::string& scenario, const std::string& description,
                              const SampleSpec& sample, const MaterialSpec& material) {
  nlohmann::json j;
  j["scenario"] = scenario;
  if (!description.empty()) j["description"] = description;
  j["dimension"] = sample.dimension;
  j["sample"] = toJson(sample);
  j["material"] = toJson(material);
  return j;
}

}  // namespace rupture::io
