#include "scenarios/piston_column/piston_column_spec.hpp"

#include <algorithm>
#include <cmath>

#include "scenarios/run_support.hpp"

namespace rupture {

namespace {

constexpr const char* kScenarioName = "piston-column";

PistonSpec parsePiston(const SpecReader& root) {
  PistonSpec p;
  const auto piston = root.optionalObject("piston");
  if (!piston) return p;
  p.motion = piston->choice("motion", {"free", "prescribed"}, "free") == "free" ? sph::BodyMotion::Free
                                                                               : sph::BodyMotion::Prescribed;
  if (p.motion == sph::BodyMotion::Free) {
    p.mass = piston->number("mass", Range::positive(), "kg", p.mass);
    if (piston->has("speed_history")) piston->fail("speed_history", "no speed_history for a free piston (motion \"prescribed\" takes one)");
  } else if (piston->has("mass")) {
    piston->fail("mass", "no mass for a prescribed piston (its motion ignores the fluid); use motion \"free\"");
  }
  p.speed = piston->number("speed", {0.0, 1e5, false, false}, "m/s", p.speed);  // io::physical::speed(), 0 allowed
  if (const auto history = piston->optionalObject("speed_history")) {
    p.history.time = history->numbers("time", 1, 10000, Range::nonNegative(), "s");
    p.history.speed = history->numbers("speed", 1, 10000, {0.0, 1e5, false, false}, "m/s");
    if (p.history.speed.size() != p.history.time.size())
      history->fail("speed", "as many speeds as times (" + std::to_string(p.history.time.size()) + ")");
    for (std::size_t k = 1; k < p.history.time.size(); ++k)
      if (!(p.history.time[k] > p.history.time[k - 1])) history->fail("time", "strictly increasing times (s)");
    history->finish();
    if (piston->has("speed")) piston->fail("speed", "either speed or speed_history, not both");
  } else {
    p.history.time = {0.0};
    p.history.speed = {p.speed};
  }
  piston->finish();
  return p;
}

}  // namespace

PistonColumnSpec parsePistonColumnSpec(const nlohmann::json& json) {
  const nlohmann::json rest = io::withoutPointArrays(json, {"probes"});  // the reader holds a reference
  const SpecReader root(rest, "");
  PistonColumnSpec s;
  io::parseFluidHead(root, kScenarioName, s);
  {
    const SpecReader geo = root.object("geometry");
    s.diameter = geo.number("diameter", Range::positive(), "m");
    s.columnHeight = geo.number("column_height", Range::positive(), "m");
    geo.finish();
  }
  s.resolution = io::parseResolution(root);
  // α = 0.3: the pressure wave's front overshoots its plateau by 9 % at 0.1 and 3 % at 0.3, while
  // 1.0 biases the plateau itself by +6 % (docs/sph.md, "Artificial viscosity and the wave front").
  s.fluid = io::parseFluid(root, 0.3);
  s.gravity = root.number("gravity", Range::nonNegative(), "m/s^2", 9.81);
  s.piston = parsePiston(root);
  if (!root.has("piston")) {
    s.piston.history.time = {0.0};
    s.piston.history.speed = {s.piston.speed};
  }
  s.run = io::parseFluidRun(root, 1e-3);
  if (const auto imp = root.optionalObject("impactor")) {
    if (root.has("piston"))
      root.fail("impactor", "either piston or impactor, not both (the impactor drives the piston)");
    if (s.dimension != 3)
      root.fail("impactor", "an impactor in 3D only (dimension 3): its piston is a bar of real section");
    s.impactor = parseImpactor(*imp, s.diameter, s.run.endTime);
    if (s.impactor->model == fsi::ImpactorModel::Rigid) {  // the free piston of mass M
      s.piston.motion = sph::BodyMotion::Free;
      s.piston.mass = s.impactor->mass;
      s.piston.speed = s.impactor->speed;
      s.piston.history = {{0.0}, {s.piston.speed}};
      s.impactor.reset();
    }
  }
  root.finish();
  s.probes = io::parseProbes(json, s.dimension);

  const double dx = s.resolution.spacing, smallest = std::min(s.diameter, s.columnHeight);
  if (dx > smallest / 4.0)
    throw SpecError("resolution.spacing", formatNumber(dx),
                    "a spacing that fits at least 4 particles across the column (<= " + formatNumber(smallest / 4.0) + " m)");
  const double layers = s.resolution.wallLayers;
  const double across = (s.diameter + 2 * layers * dx) / dx;
  const double particles = across * (s.dimension == 3 ? across : 1.0) * (s.columnHeight / dx + 4 * layers);
  if (particles > 5e6)  // about 1 kB per particle (io::estimateFluidRun): 5 GB
    throw SpecError("resolution.spacing", formatNumber(dx),
                    "a spacing giving at most 5e6 particles (this one gives about " + formatNumber(std::round(particles)) + ")");
  s.estimatedParticles = particles;
  s.soundSpeed = s.fluid.soundSpeed ? *s.fluid.soundSpeed : 1450.0;
  const double R = 0.5 * s.diameter;
  for (std::size_t k = 0; k < s.probes.size(); ++k) {
    const auto& p = s.probes[k];
    const double radial = s.dimension == 3 ? std::hypot(p[0], p[1]) : std::fabs(p[0]);
    const double vertical = s.dimension == 3 ? p[2] : p[1];
    if (!(radial <= R && vertical >= 0 && vertical <= s.columnHeight))
      throw SpecError("probes[" + std::to_string(k) + "]", io::describeValue(io::probesJson({p}, s.dimension)[0]),
                      "a point inside the water column: " +
                          std::string(s.dimension == 3 ? "sqrt(x^2 + y^2)" : "|x|") + " <= " + formatNumber(R) + " m, " +
                          (s.dimension == 3 ? "z" : "y") + " in [0, " + formatNumber(s.columnHeight) +
                          "] m (the tube axis is at the origin, the bottom at 0)");
  }
  return s;
}

nlohmann::json toJson(const PistonColumnSpec& s) {
  nlohmann::json j = {{"scenario", kScenarioName}};
  if (!s.description.empty()) j["description"] = s.description;
  j["dimension"] = s.dimension;
  j["geometry"] = {{"diameter", s.diameter}, {"column_height", s.columnHeight}};
  j["resolution"] = io::toJson(s.resolution);
  j["fluid"] = io::toJson(s.fluid, s.soundSpeed);
  j["gravity"] = s.gravity;
  nlohmann::json piston = {{"motion", sph::toString(s.piston.motion)}};
  if (s.piston.motion == sph::BodyMotion::Free) {
    piston["mass"] = s.piston.mass;
    piston["speed"] = s.piston.speed;
  } else {
    piston["speed_history"] = {{"time", s.piston.history.time}, {"speed", s.piston.history.speed}};
  }
  if (s.impactor) j["impactor"] = toJson(*s.impactor);
  else j["piston"] = piston;
  j["probes"] = io::probesJson(s.probes, s.dimension);
  j["run"] = io::toJson(s.run);
  return j;
}

}  // namespace rupture
