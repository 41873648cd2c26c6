#include "io/unknown_keys.hpp"

#include <algorithm>
#include <regex>

#include "io/spec_reader.hpp"
#include "rupture/spec_error.hpp"

namespace rupture::io {

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string nearestKey(const std::string& key, const std::vector<std::string>& allowed) {
  std::string best;
  std::size_t bestDistance = std::string::npos;
  for (const std::string& candidate : allowed) {
    const std::size_t d = editDistance(key, candidate);
    if (d < bestDistance) {
      bestDistance = d;
      best = candidate;
    }
  }
  if (best.empty()) return {};
  const std::size_t longer = std::max(key.size(), best.size());
  const std::size_t limit = std::min<std::size_t>(2, (longer + 2) / 3);
  // Same letters in another case is a typo too ("Strain_Rate").
  std::string lowerKey = key, lowerBest = best;
  std::transform(lowerKey.begin(), lowerKey.end(), lowerKey.begin(), ::tolower);
  std::transform(lowerBest.begin(), lowerBest.end(), lowerBest.begin(), ::tolower);
  return bestDistance <= limit || lowerKey == lowerBest ? best : std::string();
}

namespace {

std::string join(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

/// The properties an object schema allows, merged with those its allOf/then branches add (the
/// branches only tighten the same keys, so the union is what may appear).
void collectProperties(const nlohmann::json& schema, std::vector<std::string>& names) {
  if (!schema.is_object()) return;
  if (auto p = schema.find("properties"); p != schema.end() && p->is_object())
    for (const auto& [k, v] : p->items())
      if (std::find(names.begin(), names.end(), k) == names.end()) names.push_back(k);
}

}  // namespace

void rejectUnknownKeys(const nlohmann::json& spec, const nlohmann::json& schema, const std::string& path) {
  if (!schema.is_object()) return;
  if (spec.is_object()) {
    const auto props = schema.find("properties");
    if (props == schema.end() || !props->is_object()) return;
    const bool closed = schema.value("additionalProperties", nlohmann::json(true)) == nlohmann::json(false);
    std::vector<std::string> allowed;
    collectProperties(schema, allowed);
    std::vector<std::regex> patterns;
    if (auto pp = schema.find("patternProperties"); pp != schema.end() && pp->is_object())
      for (const auto& [pattern, sub] : pp->items()) patterns.emplace_back(pattern);
    for (auto it = spec.begin(); it != spec.end(); ++it) {
      const std::string& key = it.key();
      if (auto sub = props->find(key); sub != props->end()) {
        rejectUnknownKeys(it.value(), *sub, join(path, key));
        continue;
      }
      const bool patterned = std::any_of(patterns.begin(), patterns.end(),
                                         [&](const std::regex& r) { return std::regex_search(key, r); });
      if (patterned || !closed) continue;
      const std::string nearest = nearestKey(key, allowed);
      std::string known;
      for (const std::string& k : allowed) known += (known.empty() ? "" : ", ") + k;
      throw SpecError(join(path, key.empty() ? "\"\"" : key), describeValue(it.value()),
                      "no such field here (unknown key)" +
                          (nearest.empty() ? std::string() : "; did you mean '" + nearest + "'?") +
                          " known keys here: " + known);
    }
  } else if (spec.is_array()) {
    if (auto items = schema.find("items"); items != schema.end() && items->is_object()) {
      for (std::size_t k = 0; k < spec.size(); ++k) rejectUnknownKeys(spec[k], *items, path + "[" + std::to_string(k) + "]");
    }
  }
}

}  // namespace rupture::io
