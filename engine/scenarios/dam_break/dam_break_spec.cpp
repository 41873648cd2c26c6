#include "scenarios/dam_break/dam_break_spec.hpp"

#include <algorithm>
#include <cmath>

#include "scenarios/run_support.hpp"

namespace rupture {

namespace {

constexpr const char* kScenarioName = "dam-break";
// About 0.6 kB per particle (neighbour lists of ~100 entries and 25 fields): 5e6 is 3 GB.
constexpr double kMaxParticles = 5e6;

DamBreakGeometry parseGeometry(const SpecReader& root, int dimension) {
  DamBreakGeometry g;
  const SpecReader geo = root.object("geometry");
  g.columnWidth = geo.number("column_width", Range::positive(), "m");
  g.columnHeight = geo.number("column_height", Range::positive(), "m");
  g.tankLength = geo.number("tank_length", {g.columnWidth, 1e308, false, false}, "m");
  g.tankHeight = geo.number("tank_height", {g.columnHeight, 1e308, false, false}, "m");
  if (dimension == 3) g.width = geo.number("width", Range::positive(), "m");
  else if (geo.has("width")) geo.fail("width", "no width in 2D (a 2D run is a vertical slice); remove it or set dimension 3");
  geo.finish();
  return g;
}

}  // namespace

DamBreakSpec parseDamBreakSpec(const nlohmann::json& json) {
  const nlohmann::json rest = io::withoutPointArrays(json, {"probes"});  // the reader holds a reference
  const SpecReader root(rest, "");
  DamBreakSpec s;
  io::parseFluidHead(root, kScenarioName, s);
  s.geometry = parseGeometry(root, s.dimension);
  s.resolution = io::parseResolution(root);
  s.fluid = io::parseFluid(root, 0.1);
  s.gravity = root.number("gravity", Range::positive(), "m/s^2", 9.81);
  s.run = io::parseFluidRun(root, 0.3);
  root.finish();
  s.probes = io::parseProbes(json, s.dimension);

  // Cross-field checks.
  const DamBreakGeometry& g = s.geometry;
  const double dx = s.resolution.spacing;
  double smallest = std::min(g.columnWidth, g.columnHeight);
  if (g.width) smallest = std::min(smallest, *g.width);
  if (dx > smallest / 4.0)
    throw SpecError("resolution.spacing", formatNumber(dx),
                    "a spacing that fits at least 4 particles across the column and tank (<= " +
                        formatNumber(smallest / 4.0) + " m)");
  const int layers = s.resolution.wallLayers;
  const double across = g.width ? (*g.width + 2 * layers * dx) / dx : 1.0;
  const double particles = (g.tankLength + 2 * layers * dx) * (g.tankHeight + layers * dx) / (dx * dx) * across;
  if (particles > kMaxParticles)
    throw SpecError("resolution.spacing", formatNumber(dx),
                    "a spacing giving at most 5e6 particles (this one gives about " + formatNumber(std::round(particles)) + ")");
  s.estimatedParticles = particles;
  s.soundSpeed = s.fluid.soundSpeed ? *s.fluid.soundSpeed : 10.0 * std::sqrt(2.0 * s.gravity * g.columnHeight);
  for (std::size_t k = 0; k < s.probes.size(); ++k) {
    const auto& p = s.probes[k];
    const double vertical = s.dimension == 3 ? p[2] : p[1];
    const bool inside = p[0] >= 0 && p[0] <= g.tankLength && vertical >= 0 && vertical <= g.tankHeight &&
                        (s.dimension == 2 || (p[1] >= 0 && p[1] <= *g.width));
    if (!inside)
      throw SpecError("probes[" + std::to_string(k) + "]", io::describeValue(io::probesJson({p}, s.dimension)[0]),
                      std::string("a point inside the tank: x in [0, ") + formatNumber(g.tankLength) + "] m" +
                          (s.dimension == 3 ? ", y in [0, " + formatNumber(*g.width) + "] m" : "") + ", " +
                          (s.dimension == 3 ? "z" : "y") + " in [0, " + formatNumber(g.tankHeight) + "] m");
  }
  return s;
}

nlohmann::json toJson(const DamBreakSpec& s) {
  nlohmann::json j = {{"scenario", kScenarioName}};
  if (!s.description.empty()) j["description"] = s.description;
  j["dimension"] = s.dimension;
  j["geometry"] = {{"column_width", s.geometry.columnWidth},
                   {"column_height", s.geometry.columnHeight},
                   {"tank_length", s.geometry.tankLength},
                   {"tank_height", s.geometry.tankHeight}};
  if (s.geometry.width) j["geometry"]["width"] = *s.geometry.width;
  j["resolution"] = io::toJson(s.resolution);
  j["fluid"] = io::toJson(s.fluid, s.soundSpeed);
  j["gravity"] = s.gravity;
  j["probes"] = io::probesJson(s.probes, s.dimension);
  j["run"] = io::toJson(s.run);
  return j;
}

}  // namespace rupture
