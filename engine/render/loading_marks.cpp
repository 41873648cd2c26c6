#include "render/loading_marks.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "rupture/quantity_text.hpp"

namespace rupture::render {
namespace {

using Json = nlohmann::json;

std::array<double, 3> vector3(const Json& v) {
  std::array<double, 3> out{};
  if (!v.is_array()) return out;
  for (std::size_t a = 0; a < 3 && a < v.size(); ++a)
    if (v[a].is_number()) out[a] = v[a].get<double>();
  return out;
}

double norm(const std::array<double, 3>& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

std::array<double, 3> unit(const std::array<double, 3>& v) {
  const double n = norm(v);
  return n > 0 ? std::array<double, 3>{v[0] / n, v[1] / n, v[2] / n} : std::array<double, 3>{};
}

/// An impact's loads: its driven regions, tractions and projectile (docs/impact.md).
void impactMarks(const Json& loading, std::vector<LoadingMark>& out) {
  auto boxes = [&](const char* key, const char* vectorKey, const char* unitName, const char* what) {
    for (const Json& r : loading.value(key, Json::array())) {
      LoadingMark m;
      m.kind = LoadingMark::Kind::BoxArrow;
      m.lo = vector3(r.value("min", Json())), m.hi = vector3(r.value("max", Json()));
      const std::array<double, 3> v = vector3(r.value(vectorKey, Json()));
      m.direction = unit(v);
      m.label = std::string(what) + " " + formatQuantity(norm(v), unitName);
      if (norm(v) > 0) out.push_back(m);
    }
  };
  boxes("velocity_regions", "velocity", "m/s", "driven at");
  boxes("tractions", "traction", "Pa", "traction");
  if (loading.contains("projectile") && loading["projectile"].is_object()) {
    const Json& p = loading["projectile"];
    LoadingMark m;
    m.kind = LoadingMark::Kind::BoxArrow;
    m.lo = m.hi = vector3(p.value("position", Json()));
    const std::array<double, 3> v = vector3(p.value("velocity", Json()));
    m.direction = unit(v);
    m.label = "projectile at " + formatQuantity(norm(v), "m/s");
    if (norm(v) > 0) out.push_back(m);
  }
}

}  // namespace

std::vector<LoadingMark> loadingMarks(const io::Hdf5File& file, const std::string& root) {
  std::vector<LoadingMark> out;
  const std::string top = root.empty() ? "/" : root, specGroup = root + "/spec";
  if (!file.exists(specGroup) || !file.hasAttribute(specGroup, "json") || !file.hasAttribute(top, "scenario"))
    return out;
  Json spec;
  std::string scenario;
  try {
    spec = Json::parse(file.readAttributeString(specGroup, "json"));
    scenario = file.readAttributeString(top, "scenario");
  } catch (const std::exception&) {
    return out;  // a picture without arrows rather than none
  }
  if (!spec.is_object()) return out;
  const Json loading = spec.value("loading", Json::object());
  if (scenario == "dynamic-tension") {
    // Tension along x (docs/dynamic-tension.md): X_min held (U_x = 0), X_max pulled at V(t).
    LoadingMark held;
    held.kind = LoadingMark::Kind::FaceHeld;
    held.axis = 0, held.side = -1;
    held.label = "held";
    out.push_back(held);
    LoadingMark pulled;
    pulled.axis = 0, pulled.side = 1, pulled.direction = {1, 0, 0};
    pulled.label = "pulled";
    if (loading.contains("strain_rate") && loading["strain_rate"].is_number())
      pulled.label.append(" at ").append(formatQuantity(loading["strain_rate"].get<double>(), "1/s"));
    out.push_back(pulled);
  } else if (scenario == "impact") {
    impactMarks(loading, out);
  } else if (scenario == "tank-impact" || scenario == "piston-column") {
    // The carriage drives the piston down onto the water's free surface (vertical axis z in 3D,
    // y in a 2D column): the water loads the bottom, the tank's plate, from above.
    const bool plane = scenario == "piston-column" && spec.value("dimension", 3) == 2;
    const Json driver = spec.value(scenario == "tank-impact" ? "impactor" : "piston", Json::object());
    LoadingMark piston;
    piston.axis = plane ? 1 : 2, piston.side = 1;
    piston.direction = {0, 0, 0};
    piston.direction[static_cast<std::size_t>(piston.axis)] = -1;
    piston.label = "piston";
    if (driver.contains("speed") && driver["speed"].is_number())
      piston.label.append(" at ").append(formatQuantity(driver["speed"].get<double>(), "m/s"));
    out.push_back(piston);
  }
  return out;
}

}  // namespace rupture::render
