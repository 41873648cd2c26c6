#pragma once
// Strict reading of a JSON spec: every value is checked against its allowed range as it is read,
// every error names the dotted field path, the value and what is allowed, and keys nobody read are
// errors too (finish()). One reader per JSON object.
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rupture/spec_error.hpp"

namespace rupture::io {

/// Allowed range of a number; bounds are inclusive unless marked open.
struct Range {
  double min = -1e308, max = 1e308;
  bool minOpen = false, maxOpen = false;
  std::string describe() const;
  bool contains(double v) const;
  static Range positive() { return {0.0, 1e308, true, false}; }
  static Range nonNegative() { return {0.0, 1e308, false, false}; }
  static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
};

class SpecReader {
public:
  SpecReader(const nlohmann::json& node, std::string path);
  /// The reader keeps a reference to `node`: a temporary would leave it dangling.
  SpecReader(nlohmann::json&& node, std::string path) = delete;

  /// The dotted path of a key in this object ("sample.porosity").
  std::string pathOf(const std::string& key) const;
  bool has(const std::string& key) const;

  SpecReader object(const std::string& key) const;                      // required
  std::optional<SpecReader> optionalObject(const std::string& key) const;

  double number(const std::string& key, const Range& range, const std::string& unit) const;
  double number(const std::string& key, const Range& range, const std::string& unit, double fallback) const;
  std::int64_t integer(const std::string& key, std::int64_t min, std::int64_t max) const;
  std::int64_t integer(const std::string& key, std::int64_t min, std::int64_t max, std::int64_t fallback) const;
  bool boolean(const std::string& key, bool fallback) const;
  std::string choice(const std::string& key, const std::vector<std::string>& allowed) const;
  std::string choice(const std::string& key, const std::vector<std::string>& allowed, const std::string& fallback) const;
  std::string string(const std::string& key, const std::string& fallback) const;
  /// An array of numbers with a length in [minLength, maxLength], each in range.
  std::vector<double> numbers(const std::string& key, std::size_t minLength, std::size_t maxLength,
                              const Range& range, const std::string& unit) const;

  /// An optional array of JSON objects ("notches": [{...}, ...]), one reader each with the path
  /// "key[k]"; empty when absent. `what` describes one element for the error message.
  std::vector<SpecReader> objects(const std::string& key, const std::string& what) const;
  /// Throws for the first key of this object that no accessor read.
  void finish() const;

  [[noreturn]] void fail(const std::string& key, const std::string& allowed) const;

  const nlohmann::json& node() const { return m_node; }
  const std::string& path() const { return m_path; }

private:
  const nlohmann::json* find(const std::string& key) const;
  const nlohmann::json& m_node;
  std::string m_path;
  mutable std::set<std::string> m_read;
};

/// Short text of a JSON value for error messages (long strings and arrays are cut).
std::string describeValue(const nlohmann::json& value);

}  // namespace rupture::io

namespace rupture {
// Every scenario's parser reads its spec with these.
using io::Range;
using io::SpecReader;
}  // namespace rupture
