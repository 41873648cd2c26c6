#include "bonded/bonded_spec.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "core/format_number.hpp"
#include "io/physical_ranges.hpp"
#include "io/run_estimate.hpp"
#include "lattice/lattice_geometry.hpp"
#include "bonded/materials/registry.hpp"

namespace rupture::io {

namespace {
// Guard against specs that would build an absurd number of elements (and exhaust memory).
constexpr double kMaxElements = 5e6;
// Pores are placed one by one (random sequential addition, engine/samples/sample_builder.cpp): bound
// their number so placement and carving stay seconds, and the porosity below the jamming limit of
// random sequential addition (0.547 for equal disks, 0.382 for equal spheres) with a margin for
// the finite box, where pore centres stay one radius away from the walls.
constexpr double kMaxPores = 1e4;
constexpr std::int64_t kMaxGrains = 100000;  // the grid search stays O(particles) whatever the count
constexpr double kMaxPorosity2D = 0.5;
constexpr double kMaxPorosity3D = 0.35;

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
  const LatticeKind kind = latticeKind(s.lattice);
  if (kind != LatticeKind::Random)  // one site per lattice cell
    return volume / (siteMeasure(kind) * std::pow(s.spacing, s.dimension)) * (1.0 - s.porosity);
  const double meanElement = (s.dimension == 2 ? std::numbers::pi : 4.0 / 3.0 * std::numbers::pi) *
                             meanPower(s.dimension, s.elementRadius * (1 - s.radiusDispersion),
                                       s.elementRadius * (1 + s.radiusDispersion));
  const double fraction = s.dimension == 2 ? 0.84 : 0.58;  // the packing's target solid fraction
  return fraction * volume / meanElement * (1.0 - s.porosity);
}

namespace {
// Peak resident memory of dynamic-tension runs divided by their elements (particle and bond
// arrays, contact lists, snapshots in flight), measured at 86k elements in 2D (0.85 kB) and 52k
// in 3D (1.15 kB), rounded up.
constexpr double kBytesPerElement2D = 1.0e3, kBytesPerElement3D = 1.5e3;
// A peridynamic bond beyond the few nearest neighbours those figures hold: its entry in the bond
// store (ends, rest length, stiffness, threshold, state), two slots of the partner lists and of
// the incidence lists. Measured on a 3D simple-cubic PMB sample of 13,200 sites (dynamic tension,
// 2026-11-27): 1,113,818 bonds at horizon_factor 3 and 5,950,724 at 6, peak resident memory 247 and
// 1,151 MB, i.e. 187 B per added bond; rounded up.
constexpr double kBytesPerPmbBond = 190;

/// Bonds per site beyond the nearest neighbours (PMB horizons), as the material style counts them.
/// PMB's upper bound on the sample above: 121 and 679 per site against 84 and 451 measured (the
/// faces lose bonds).
LongRangeBonds longRangeBonds(const SampleSpec& s, const MaterialSpec& m) {
  return materialStyle(m.model).longRangeBonds(s, m);
}
}  // namespace

double estimatedMemoryBytes(const SampleSpec& s, const MaterialSpec& m) {
  const double perElement = s.dimension == 2 ? kBytesPerElement2D : kBytesPerElement3D;
  return kRunBaseBytes + estimatedElements(s) * (perElement + longRangeBonds(s, m).perSite * kBytesPerPmbBond);
}

RunEstimate estimateBondedRun(const SampleSpec& sample, const MaterialSpec& material) {
  RunEstimate e;
  e.particles = estimatedElements(sample);
  e.memoryBytes = estimatedMemoryBytes(sample, material);
  e.field = sample.lattice == "random" ? "sample.element_radius" : "sample.spacing";
  std::ostringstream basis;
  basis << formatNumber(kRunBaseBytes / 1048576.0) << " MiB and " << (sample.dimension == 2 ? kBytesPerElement2D : kBytesPerElement3D) << " B per element";
  if (const LongRangeBonds bonds = longRangeBonds(sample, material); bonds.perSite > 0)
    basis << " and " << kBytesPerPmbBond << " B per bond, " << std::lround(bonds.perSite) << " bonds per site "
          << bonds.basis;
  e.basis = basis.str();
  return e;
}

namespace {
// dt_c / (d / c): the critical step over the transit time of the bar wave c = √(E/ρ) (E the
// model's: beams E_μ r_μ², lattice springs and PMB their E) across the smallest element's diameter
// d (lattices: the spacing). Measured on the examples' samples (2026-12-04): 0.29-0.36 for beams
// on random packings, 0.42 for Born and 0.58 for Hookean springs, 1.13 for PMB at horizon factor 3
// (its stiffness falls as δ⁻⁴ over a bond count that grows as δ³). The smallest, so that the
// estimate errs towards more steps (four times as many for PMB).
constexpr double kStepPerTransit = 0.29;
}  // namespace

double estimatedCriticalStep(const SampleSpec& s, const MaterialSpec& m) {
  const double diameter =
      s.lattice == "random" ? 2.0 * s.elementRadius * (1.0 - s.radiusDispersion) : s.spacing;
  double waveSpeed = m.dampingWaveSpeed;  // √(E/ρ) of the model's E
  // Stiffer or lighter inclusions carry a faster wave.
  if (s.inclusions.volumeFraction > 0)
    waveSpeed *= std::max(1.0, std::sqrt(s.inclusions.stiffnessFactor / s.inclusions.densityFactor));
  return kStepPerTransit * diameter / waveSpeed;
}

std::string bondedStepRule() {
  return "time step " + formatNumber(kStepPerTransit) +
         " d / sqrt(E/rho) x run.time_step_safety (d the smallest element's diameter or the lattice spacing, E the "
         "model's Young's modulus, beams E_mu r_mu^2, rho material.density)";
}

SampleSpec parseSample(const SpecReader& root) {
  SampleSpec s;
  s.dimension = static_cast<int>(root.integer("dimension", 2, 3));
  const SpecReader sample = root.object("sample");
  const std::size_t d = static_cast<std::size_t>(s.dimension);
  s.lattice = sample.choice("lattice", {"random", "triangular", "square", "simple-cubic", "fcc"}, "random");
  const LatticeKind kind = latticeKind(s.lattice);
  if (kind != LatticeKind::Random && latticeDimension(kind) != s.dimension)
    sample.fail("lattice", s.dimension == 2 ? "\"random\", \"triangular\" or \"square\" when dimension is 2"
                                            : "\"random\", \"simple-cubic\" or \"fcc\" when dimension is 3");
  const auto size = sample.numbers("size", d, d, Range::positive(), "m");
  for (std::size_t a = 0; a < d; ++a) s.size[a] = size[a];
  const bool lattice = kind != LatticeKind::Random;
  if (lattice) {
    s.spacing = sample.number("spacing", Range::positive(), "m");
    s.elementRadius = 0.5 * s.spacing;  // node radius l/2 (contact after breakage, docs/references.md#eq-lattice)
    if (s.dimension == 2) s.thickness = sample.number("thickness", Range::positive(), "m", s.spacing);
  } else {
    s.elementRadius = sample.number("element_radius", Range::positive(), "m");
    s.radiusDispersion = sample.number("radius_dispersion", Range::closed(0.0, 0.5), "1", s.radiusDispersion);
    s.bondGap = sample.number("bond_gap", Range::closed(0.0, 1.0), "1", s.bondGap);
  }
  // An element wider than the sample: the builder would pack one squeezed element (or, on a
  // lattice, no site) across that edge. One element diameter is the least an edge can hold.
  const double diameter = lattice ? s.spacing : 2.0 * s.elementRadius;
  for (std::size_t a = 0; a < d; ++a)
    if (size[a] < diameter)
      throw SpecError(sample.pathOf("size") + "[" + std::to_string(a) + "]", formatNumber(size[a]),
                      "an edge at least one element wide (" +
                          std::string(lattice ? "sample.spacing" : "2 x sample.element_radius") + " = " +
                          formatNumber(diameter) + " m)");
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
      sample.fail("pore_radius", std::string("pore radii >= ") + (lattice ? "half the sample.spacing" : "sample.element_radius") +
                                     " (" + formatNumber(s.elementRadius) + " m)");
  }
  s.seed = static_cast<std::uint64_t>(sample.integer("seed", 0, (std::int64_t{1} << 53), 1));
  for (const SpecReader& notch : sample.objects("notches", "{\"start\": [x, y(, z)], \"end\": [...]} (m)")) {
    Notch n;
    const auto a = notch.numbers("start", d, d, Range{}, "m");
    const auto b = notch.numbers("end", d, d, Range{}, "m");
    for (std::size_t k = 0; k < d; ++k) { n.start[k] = a[k]; n.end[k] = b[k]; }
    if (a == b) notch.fail("end", "a point different from start (m)");
    notch.finish();
    s.notches.push_back(n);
  }
  for (const SpecReader& block : sample.objects("blocks", "{\"id\": 2, \"min\": [...], \"max\": [...]} (m)")) {
    BlockRegion b;
    b.id = static_cast<int>(block.integer("id", 1, 999));
    const auto lo = block.numbers("min", d, d, Range{}, "m");
    const auto hi = block.numbers("max", d, d, Range{}, "m");
    for (std::size_t k = 0; k < d; ++k) {
      if (lo[k] > hi[k]) block.fail("max", "a corner with every coordinate >= min's (m)");
      b.box.min[k] = lo[k];
      b.box.max[k] = hi[k];
    }
    if (d == 2) { b.box.min[2] = -1e308; b.box.max[2] = 1e308; }
    block.finish();
    s.blocks.push_back(b);
  }
  if (auto grains = sample.optionalObject("grains")) {
    s.grains.count = static_cast<int>(grains->integer("count", 2, kMaxGrains));
    s.grains.boundaryFactor = grains->number("boundary_factor", {0.0, 10.0, true, false}, "1", 1.0);
    grains->finish();
  }
  if (auto inclusions = sample.optionalObject("inclusions")) {
    InclusionSpec& c = s.inclusions;
    c.volumeFraction = inclusions->number("volume_fraction", {0.0, 0.5, true, false}, "1");
    const auto radius = inclusions->numbers("radius", 2, 2, Range::positive(), "m");
    if (radius[0] > radius[1]) inclusions->fail("radius", "[min, max] with min <= max (m)");
    c.radius = {radius[0], radius[1]};
    const double smallestEdge = *std::min_element(size.begin(), size.end());
    if (2.0 * radius[1] >= smallestEdge) inclusions->fail("radius", "diameters smaller than the smallest sample edge");
    if (radius[0] < s.elementRadius)
      inclusions->fail("radius", std::string("radii >= ") + (lattice ? "half the sample.spacing" : "sample.element_radius") +
                                     " (" + formatNumber(s.elementRadius) + " m)");
    const Range factor{0.0, 100.0, true, false};
    c.stiffnessFactor = inclusions->number("stiffness_factor", factor, "1", 1.0);
    c.strengthFactor = inclusions->number("strength_factor", factor, "1", 1.0);
    c.interfaceStrengthFactor = inclusions->number("interface_strength_factor", factor, "1", 1.0);
    c.densityFactor = inclusions->number("density_factor", factor, "1", 1.0);
    inclusions->finish();
  }
  sample.finish();

  double volume = 1;
  for (std::size_t a = 0; a < d; ++a) volume *= s.size[a];
  const std::string key = lattice ? "spacing" : "element_radius";
  const double value = lattice ? s.spacing : s.elementRadius;
  const double estimate = volume / (lattice ? siteMeasure(kind) * std::pow(s.spacing, s.dimension)
                                            : ballVolume(s.dimension, s.elementRadius));
  if (estimate > kMaxElements)
    throw SpecError(sample.pathOf(key), formatNumber(value),
                    "a value giving at most 5e6 elements for this sample.size (this gives about " +
                        formatNumber(std::round(estimate)) + ")");
  if (estimate < 8)
    throw SpecError(sample.pathOf(key), formatNumber(value),
                    "a value small enough for at least 8 elements in sample.size");
  if (s.inclusions.volumeFraction > 0) {
    const double count = s.inclusions.volumeFraction * volume /
                         ((s.dimension == 2 ? std::numbers::pi : 4.0 / 3.0 * std::numbers::pi) *
                          meanPower(s.dimension, s.inclusions.radius[0], s.inclusions.radius[1]));
    if (count > kMaxPores)
      throw SpecError(sample.pathOf("inclusions") + ".radius",
                      "[" + formatNumber(s.inclusions.radius[0]) + ", " + formatNumber(s.inclusions.radius[1]) + "]",
                      "radii large enough for at most 10000 inclusions at this volume_fraction and sample.size (these need about " +
                          formatNumber(std::round(count)) + ")");
  }
  // Pores or inclusions that cannot fit: when one of the largest radius holds less than the
  // fraction asks for, the builder must place a second; the centres of those of radius >= r_min lie
  // at least r_min from every face, and two of them must be 2 r_min apart. A box whose inner
  // diagonal is shorter holds only one, and the builder would give up after its attempts
  // (samples/pores.cpp).
  auto requireRoomForTwo = [&](const std::string& field, double fraction, const std::array<double, 2>& radius,
                               const std::string& radiusName) {
    const double rMin = radius[0];
    double diagonal2 = 0;
    for (std::size_t a = 0; a < d; ++a) diagonal2 += (s.size[a] - 2.0 * rMin) * (s.size[a] - 2.0 * rMin);
    const double one = ballVolume(s.dimension, radius[1]);
    if (fraction * volume > one && diagonal2 < 4.0 * rMin * rMin)
      throw SpecError(field, formatNumber(fraction),
                      "at most " + formatNumber(one / volume) + " (one of the largest " + radiusName +
                          "): two of radius >= " + formatNumber(rMin) +
                          " m do not fit side by side in this sample.size; lower it or the radii");
  };
  if (s.inclusions.volumeFraction > 0)
    requireRoomForTwo(sample.pathOf("inclusions") + ".volume_fraction", s.inclusions.volumeFraction,
                      s.inclusions.radius, "sample.inclusions.radius");
  if (s.porosity > 0) requireRoomForTwo(sample.pathOf("porosity"), s.porosity, s.poreRadius, "sample.pore_radius");
  if (s.porosity > 0) {
    const double pores = s.porosity * volume /
                         ((s.dimension == 2 ? std::numbers::pi : 4.0 / 3.0 * std::numbers::pi) *
                          meanPower(s.dimension, s.poreRadius[0], s.poreRadius[1]));
    if (pores > kMaxPores)
      throw SpecError(sample.pathOf("pore_radius"), "[" + formatNumber(s.poreRadius[0]) + ", " + formatNumber(s.poreRadius[1]) + "]",
                      "pore radii large enough for at most 10000 pores at this porosity and sample.size (these need about " +
                          formatNumber(std::round(pores)) + ")");
  }
  return s;
}

namespace {

/// sample.<key> of the raw spec, or null: the material's parsing reads a few sample fields (the
/// sample itself is validated on its own).
const nlohmann::json* rawSampleMember(const SpecReader& root, const std::string& key) {
  const auto& node = root.node();
  if (!node.contains("sample") || !node["sample"].is_object() || !node["sample"].contains(key)) return nullptr;
  return &node["sample"][key];
}

/// The lattice named by the (already validated) sample: the material's admissible range depends on it.
LatticeKind rawLattice(const SpecReader& root) {
  if (const auto* lattice = rawSampleMember(root, "lattice"); lattice && lattice->is_string()) {
    try {
      return latticeKind(lattice->get<std::string>());
    } catch (const std::invalid_argument&) {
    }
  }
  return LatticeKind::Random;
}

int rawDimension(const SpecReader& root) {
  const auto& node = root.node();
  return node.contains("dimension") && node["dimension"].is_number_integer() ? node["dimension"].get<int>() : 2;
}

void requireLattice(const SpecReader& material, LatticeKind lattice, const std::vector<LatticeKind>& allowed,
                    const std::string& model) {
  for (LatticeKind k : allowed)
    if (k == lattice) return;
  std::string names;
  for (LatticeKind k : allowed) names += (names.empty() ? "" : ", ") + ("sample.lattice \"" + toString(k) + "\"");
  throw SpecError(material.pathOf("model"), "\"" + model + "\"",
                  "\"" + model + "\" on " + names + " (this sample is \"" + toString(lattice) + "\")");
}

Box parseBox(const SpecReader& box, int dimension) {
  const std::size_t d = static_cast<std::size_t>(dimension);
  Box b;
  const auto lo = box.numbers("min", d, d, Range{}, "m");
  const auto hi = box.numbers("max", d, d, Range{}, "m");
  for (std::size_t k = 0; k < d; ++k) {
    if (lo[k] > hi[k]) box.fail("max", "a corner with every coordinate >= min's (m)");
    b.min[k] = lo[k];
    b.max[k] = hi[k];
  }
  if (d == 2) { b.min[2] = -1e308; b.max[2] = 1e308; }
  return b;
}

/// One factor of material.disorder: {"distribution": "weibull", "modulus": m} or
/// {"distribution": "normal", "cv": c}.
FactorDistribution parseFactorDistribution(const SpecReader& factor) {
  FactorDistribution d;
  const std::string kind = factor.choice("distribution", {"weibull", "normal"});
  if (kind == "weibull") {
    d.kind = FactorDistribution::Kind::Weibull;
    d.weibullModulus = factor.number("modulus", Range::closed(0.5, 1000.0), "1");
  } else {
    d.kind = FactorDistribution::Kind::Normal;
    // Up to 0.3 the ±3 sd truncation keeps every factor positive (>= 0.1) and the mean at 1.
    d.variation = factor.number("cv", Range::closed(0.0, 0.3), "1");
  }
  factor.finish();
  return d;
}

std::uint64_t rawSampleSeed(const SpecReader& root) {
  const auto* seed = rawSampleMember(root, "seed");
  return seed && seed->is_number_unsigned() ? seed->get<std::uint64_t>() : 1;  // 1: the sample's default
}

int rawGrainCount(const SpecReader& root) {
  const auto* grains = rawSampleMember(root, "grains");
  if (!grains || !grains->is_object() || !grains->contains("count") || !(*grains)["count"].is_number_integer()) return 0;
  return (*grains)["count"].get<int>();
}

/// A block id of material.anisotropic_damage.block_angles ("1" … "999").
int blockIdOf(const SpecReader& object, const std::string& key) {
  std::size_t used = 0;
  int id = 0;
  try {
    id = std::stoi(key, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != key.size() || id < 1 || id > 999)
    throw SpecError(object.pathOf(key), describeValue(object.node()[key]), "keys that are block ids in [1, 999]");
  return id;
}

/// material.anisotropic_damage: the critical factors along the material axes and the frames.
AnisotropicDamageSpec parseAnisotropicDamage(const SpecReader& a, const SpecReader& root) {
  AnisotropicDamageSpec spec;
  const int dimension = rawDimension(root);
  const std::size_t d = static_cast<std::size_t>(dimension), angleCount = dimension == 2 ? 1 : 3;
  spec.criticalFactors = a.numbers("critical_factors", d, d, {0.0, 100.0, true, false}, "1");
  auto readAngles = [&](const SpecReader& reader, const std::string& key) {
    const std::vector<double> degrees = reader.numbers(key, angleCount, angleCount, Range::closed(-360, 360), "deg");
    FrameAngles angles{0, 0, 0};
    for (std::size_t k = 0; k < angleCount; ++k) angles[k] = degrees[k];
    return angles;
  };
  if (a.has("angles")) spec.angles = readAngles(a, "angles");
  if (auto blocks = a.optionalObject("block_angles")) {
    for (const auto& [key, value] : blocks->node().items()) spec.blockAngles[blockIdOf(*blocks, key)] = readAngles(*blocks, key);
    blocks->finish();
  }
  spec.randomGrainFrames = a.choice("grain_frames", {"none", "random"}, "none") == "random";
  if (spec.randomGrainFrames && rawGrainCount(root) < 2)
    a.fail("grain_frames", "\"none\" unless sample.grains has a count of 2 or more (\"random\" gives each grain its own frame)");
  if (spec.randomGrainFrames && (a.has("angles") || a.has("block_angles")))
    a.fail("grain_frames", "\"none\" when angles or block_angles set the frames (give one way)");
  a.finish();
  return spec;
}

nlohmann::json toJson(const FactorDistribution& d) {
  if (d.kind == FactorDistribution::Kind::Weibull) return {{"distribution", "weibull"}, {"modulus", d.weibullModulus}};
  return {{"distribution", "normal"}, {"cv", d.variation}};
}

}  // namespace

MaterialSpec parseMaterial(const SpecReader& root) {
  MaterialSpec m;
  const SpecReader material = root.object("material");
  const LatticeKind lattice = rawLattice(root);
  m.model = material.choice("model", materialStyleNames());
  m.density = material.number("density", physical::density(), "kg/m^3");
  const MaterialStyle& style = materialStyle(m.model);
  if (const std::vector<LatticeKind> allowed = style.lattices(); !allowed.empty())
    requireLattice(material, lattice, allowed, m.model);
  style.parse(material, MaterialContext{lattice, rawDimension(root), root.node()}, m);
  const double contactModulus = m.contact.youngModulus;
  m.localDamping = material.number("local_damping", Range::closed(0.0, 10.0), "1", 0.0);
  m.dampingWaveSpeed = std::sqrt(contactModulus / m.density);  // the model's E (beams: E_μ r², as contact)
  if (auto contact = material.optionalObject("contact")) {
    m.contact.enabled = contact->boolean("enabled", true);
    m.contactModulusFromBeams = m.contactModulusFromBeams && !contact->has("young_modulus");
    m.contactPoissonFromBeams = m.contactPoissonFromBeams && !contact->has("poisson_ratio");
    m.contact.youngModulus = contact->number("young_modulus", physical::modulus(), "Pa", m.contact.youngModulus);
    m.contact.poissonRatio = contact->number("poisson_ratio", {-1.0, 0.5, true, true}, "1", m.contact.poissonRatio);
    m.contact.friction = contact->number("friction", Range::closed(0.0, 2.0), "1", m.contact.friction);
    m.contact.dampingRatio = contact->number("damping_ratio", Range::closed(0.0, 1.0), "1", m.contact.dampingRatio);
    contact->finish();
  }
  if (auto interblock = material.optionalObject("interblock")) {
    if (style.criterion(m) != "critical_stretch")
      material.fail("interblock", "absent unless the criterion is \"critical_stretch\" (interblock values are critical stretches)");
    for (const auto& [key, value] : interblock->node().items()) {
      const auto sep = key.find('_');
      int a = 0, b = 0;
      try {
        if (sep == std::string::npos) throw std::invalid_argument(key);
        std::size_t used = 0;
        a = std::stoi(key.substr(0, sep), &used);
        if (used != sep) throw std::invalid_argument(key);
        b = std::stoi(key.substr(sep + 1), &used);
        if (used != key.size() - sep - 1) throw std::invalid_argument(key);
      } catch (const std::exception&) {
        throw SpecError(interblock->pathOf(key), describeValue(value), "keys \"a_b\" with block ids a, b in [1, 999]");
      }
      if (a < 1 || a > 999 || b < 1 || b > 999)
        throw SpecError(interblock->pathOf(key), describeValue(value), "keys \"a_b\" with block ids a, b in [1, 999]");
      m.interblock[a * 1000 + b] = interblock->number(key, Range::positive(), "1");
    }
    interblock->finish();
  }
  for (const SpecReader& box : material.objects("no_failure_regions", "{\"min\": [...], \"max\": [...]} (m)")) {
    m.noFailureRegions.push_back(parseBox(box, rawDimension(root)));
    box.finish();
  }
  if (auto anisotropic = material.optionalObject("anisotropic_damage"))
    m.anisotropicDamage = parseAnisotropicDamage(*anisotropic, root);
  if (auto disorder = material.optionalObject("disorder")) {
    // Its own seed; by default the sample's, so that replicates over sample.seed vary both.
    m.disorder.seed = static_cast<std::uint64_t>(
        disorder->integer("seed", 0, std::int64_t{1} << 53, static_cast<std::int64_t>(rawSampleSeed(root))));
    if (auto strength = disorder->optionalObject("strength")) m.disorder.strength = parseFactorDistribution(*strength);
    if (auto stiffness = disorder->optionalObject("stiffness")) m.disorder.stiffness = parseFactorDistribution(*stiffness);
    if (!m.disorder.any())
      material.fail("disorder", "an object with \"strength\" or \"stiffness\" (or both), e.g. "
                                "{\"strength\": {\"distribution\": \"weibull\", \"modulus\": 6}}");
    disorder->finish();
  }
  material.finish();
  return m;
}

namespace {
nlohmann::json point(const std::array<double, 3>& p, int dimension) {
  nlohmann::json a = nlohmann::json::array();
  for (int k = 0; k < dimension; ++k) a.push_back(p[k]);
  return a;
}
}  // namespace

nlohmann::json toJson(const SampleSpec& s) {
  nlohmann::json size = nlohmann::json::array();
  for (int a = 0; a < s.dimension; ++a) size.push_back(s.size[a]);
  nlohmann::json j = {{"lattice", s.lattice}, {"size", size}, {"porosity", s.porosity}, {"seed", s.seed}};
  if (s.lattice == "random") {
    j["element_radius"] = s.elementRadius;
    j["radius_dispersion"] = s.radiusDispersion;
    j["bond_gap"] = s.bondGap;
  } else {
    j["spacing"] = s.spacing;
    if (s.dimension == 2) j["thickness"] = s.thickness;
  }
  if (s.porosity > 0) j["pore_radius"] = {s.poreRadius[0], s.poreRadius[1]};
  if (!s.blocks.empty()) {
    j["blocks"] = nlohmann::json::array();
    for (const BlockRegion& b : s.blocks)
      j["blocks"].push_back({{"id", b.id}, {"min", point(b.box.min, s.dimension)}, {"max", point(b.box.max, s.dimension)}});
  }
  if (s.inclusions.volumeFraction > 0) {
    const InclusionSpec& c = s.inclusions;
    j["inclusions"] = {{"volume_fraction", c.volumeFraction}, {"radius", {c.radius[0], c.radius[1]}},
                       {"stiffness_factor", c.stiffnessFactor}, {"strength_factor", c.strengthFactor},
                       {"interface_strength_factor", c.interfaceStrengthFactor}, {"density_factor", c.densityFactor}};
  }
  if (s.grains.count > 0) {
    j["grains"] = {{"count", s.grains.count}, {"boundary_factor", s.grains.boundaryFactor}};
  }
  if (!s.notches.empty()) {
    j["notches"] = nlohmann::json::array();
    for (const Notch& n : s.notches)
      j["notches"].push_back({{"start", point(n.start, s.dimension)}, {"end", point(n.end, s.dimension)}});
  }
  return j;
}

nlohmann::json toJson(const MaterialSpec& m) {
  nlohmann::json j = {{"model", m.model}, {"density", m.density}};
  j[m.model] = materialStyle(m.model).toJson(m);
  j["contact"] = {{"enabled", m.contact.enabled},
                  {"young_modulus", m.contact.youngModulus},
                  {"poisson_ratio", m.contact.poissonRatio},
                  {"friction", m.contact.friction},
                  {"damping_ratio", m.contact.dampingRatio}};
  j["local_damping"] = m.localDamping;
  if (!m.interblock.empty()) {
    j["interblock"] = nlohmann::json::object();
    for (const auto& [key, value] : m.interblock) j["interblock"][std::to_string(key / 1000) + "_" + std::to_string(key % 1000)] = value;
  }
  if (!m.noFailureRegions.empty()) {
    j["no_failure_regions"] = nlohmann::json::array();
    for (const Box& b : m.noFailureRegions) {
      const int d = b.min[2] < -1e307 ? 2 : 3;
      j["no_failure_regions"].push_back({{"min", point(b.min, d)}, {"max", point(b.max, d)}});
    }
  }
  if (m.anisotropicDamage.enabled()) {
    const AnisotropicDamageSpec& a = m.anisotropicDamage;
    const int d = static_cast<int>(a.criticalFactors.size());
    auto degrees = [&](const FrameAngles& angles) {
      nlohmann::json out = nlohmann::json::array();
      for (int k = 0; k < (d == 2 ? 1 : 3); ++k) out.push_back(angles[k]);
      return out;
    };
    j["anisotropic_damage"] = {{"critical_factors", a.criticalFactors},
                               {"grain_frames", a.randomGrainFrames ? "random" : "none"}};
    if (!a.randomGrainFrames) j["anisotropic_damage"]["angles"] = degrees(a.angles);
    if (!a.blockAngles.empty()) {
      j["anisotropic_damage"]["block_angles"] = nlohmann::json::object();
      for (const auto& [id, angles] : a.blockAngles) j["anisotropic_damage"]["block_angles"][std::to_string(id)] = degrees(angles);
    }
  }
  if (m.disorder.any()) {
    j["disorder"] = {{"seed", m.disorder.seed}};
    if (m.disorder.strength.kind != FactorDistribution::Kind::None) j["disorder"]["strength"] = toJson(m.disorder.strength);
    if (m.disorder.stiffness.kind != FactorDistribution::Kind::None) j["disorder"]["stiffness"] = toJson(m.disorder.stiffness);
  }
  return j;
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
