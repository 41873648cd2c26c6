#pragma once
// Unknown keys, found from the scenario's JSON Schema before any value is read, so that a typo in a
// required key ("strain_rte") is reported as the unknown key it is, with the nearest allowed key,
// rather than as the required key being "(missing)".
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rupture::io {

/// Levenshtein distance (insertions, deletions, substitutions; ASCII bytes).
std::size_t editDistance(const std::string& a, const std::string& b);

/// The allowed key closest to `key`, or "" when none is close enough to be a likely typo
/// (distance at most 2, and at most a third of the longer name, rounded up).
std::string nearestKey(const std::string& key, const std::vector<std::string>& allowed);

/// Walks `spec` along `schema` (properties, items, additionalProperties: false, patternProperties)
/// and throws SpecError for the first key an object's schema does not allow, in document order:
/// field = its dotted path, allowed = "no such field here (unknown key); did you mean 'x'? known
/// keys here: a, b, c". Objects whose schema lists no properties are not checked.
void rejectUnknownKeys(const nlohmann::json& spec, const nlohmann::json& schema, const std::string& path = "");

}  // namespace rupture::io
