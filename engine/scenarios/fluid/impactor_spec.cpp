#include "scenarios/fluid/impactor_spec.hpp"

#include <cmath>

#include "core/format_number.hpp"

namespace rupture {

using fsi::ImpactorColumn;
using fsi::ImpactorModel;
using fsi::ImpactorSpec;

using io::Range;

ImpactorSpec parseImpactor(const io::SpecReader& r, double bore, double endTime) {
  ImpactorSpec s;
  s.pistonDiameter = bore;
  const std::string model = r.choice("model", {"rigid", "two_body", "elastic_piston"}, toString(s.model));
  s.model = model == "rigid" ? ImpactorModel::Rigid : model == "two_body" ? ImpactorModel::TwoBody : ImpactorModel::ElasticPiston;
  s.mass = r.number("mass", Range::positive(), "kg", s.mass);
  s.speed = r.number("speed", {0.0, 1e5, false, false}, "m/s", s.speed);  // io::physical::speed(), 0 allowed
  if (s.model == ImpactorModel::Rigid) {
    for (const char* key : {"piston", "contact_stiffness", "contact"})
      if (r.has(key))
        r.fail(key, std::string("no ") + key + " for the rigid impactor (carriage and piston one body of mass `mass`); "
                                                 "use model \"two_body\" or \"elastic_piston\"");
    r.finish();
    return s;
  }
  if (const auto p = r.optionalObject("piston")) {
    s.pistonLength = p->number("length", Range{0.0, 10.0, true, false}, "m", s.pistonLength);
    s.pistonDiameter = p->number("diameter", Range{0.0, 10.0, true, false}, "m", s.pistonDiameter);
    s.pistonYoungModulus = p->number("young_modulus", Range{1e6, 1e13, false, false}, "Pa", s.pistonYoungModulus);
    if (p->has("mass") && p->has("density"))
      p->fail("mass", "either mass or density, not both (the mass sets the density: mass / (π diameter²/4 × length))");
    if (p->has("mass"))
      s.pistonDensity = p->number("mass", Range::positive(), "kg") / (s.pistonArea() * s.pistonLength);
    else
      s.pistonDensity = p->number("density", Range{1.0, 1e5, false, false}, "kg/m^3", s.pistonDensity);
    if (s.model == ImpactorModel::ElasticPiston)
      s.pistonElements = static_cast<int>(p->integer("elements", 1, 1000, s.pistonElements));
    else if (p->has("elements"))
      p->fail("elements", "no elements for a rigid piston (model \"two_body\"); use model \"elastic_piston\"");
    p->finish();
  }
  s.contactStiffness = r.number("contact_stiffness", Range{0.0, 1e16, true, false}, "N/m", s.resolvedContactStiffness());
  s.contact = r.choice("contact", {"compression_only", "tied"}, toString(s.contact)) == "tied"
                  ? fsi::CarriageContact::Tied
                  : fsi::CarriageContact::CompressionOnly;
  r.finish();
  // The column must finish: its sub-steps over the run, times its points, are bounded.
  const ImpactorColumn column(s, 0.0);
  const double pointSteps = std::ceil(endTime / column.stableTimeStep()) * static_cast<double>(column.nodes());
  if (pointSteps > 1e9) {
    const std::string cost = "a column that steps at most 1e9 point-steps over run.end_time (this one: stable step " +
                             formatNumber(column.stableTimeStep()) + " s, " + std::to_string(column.nodes()) +
                             " points, " + formatNumber(pointSteps) + " point-steps)";
    // Name what the user chose: the contact and piston they gave, else the run's length.
    if (r.has("contact_stiffness") || r.has("piston"))
      throw SpecError(r.pathOf("contact_stiffness"), formatNumber(s.contactStiffness),
                      cost + ": a softer contact, fewer piston.elements or a longer piston");
    throw SpecError("run.end_time", formatNumber(endTime), cost + ": a shorter run");
  }
  return s;
}

nlohmann::json toJson(const ImpactorSpec& s) {
  nlohmann::json j = {{"model", toString(s.model)}, {"mass", s.mass}, {"speed", s.speed}};
  if (s.model == ImpactorModel::Rigid) return j;
  j["piston"] = {{"length", s.pistonLength},
                 {"diameter", s.pistonDiameter},
                 {"density", s.pistonDensity},
                 {"young_modulus", s.pistonYoungModulus}};
  if (s.model == ImpactorModel::ElasticPiston) j["piston"]["elements"] = s.pistonElements;
  j["contact_stiffness"] = s.resolvedContactStiffness();
  j["contact"] = toString(s.contact);
  return j;
}

}  // namespace rupture
