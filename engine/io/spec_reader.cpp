#include "io/spec_reader.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace rupture::io {

namespace {
std::string formatNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
}  // namespace

std::string Range::describe() const {
  std::ostringstream s;
  if (min <= -1e308 && max >= 1e308) return "any number";
  if (max >= 1e308) {
    s << (minOpen ? "> " : ">= ") << formatNumber(min);
  } else if (min <= -1e308) {
    s << (maxOpen ? "< " : "<= ") << formatNumber(max);
  } else {
    s << (minOpen ? "(" : "[") << formatNumber(min) << ", " << formatNumber(max) << (maxOpen ? ")" : "]");
  }
  return s.str();
}

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  if (minOpen ? v <= min : v < min) return false;
  if (maxOpen ? v >= max : v > max) return false;
  return true;
}

std::string describeValue(const nlohmann::json& value) {
  std::string text = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (text.size() > 80) {
    std::size_t cut = 77;  // back to the first byte of a UTF-8 character: never cut one in half
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
    text = text.substr(0, cut) + "...";
  }
  return text;
}

SpecReader::SpecReader(const nlohmann::json& node, std::string path) : m_node(node), m_path(std::move(path)) {
  if (!m_node.is_object())
    throw SpecError(m_path.empty() ? "(root)" : m_path, describeValue(m_node), "a JSON object");
}

std::string SpecReader::pathOf(const std::string& key) const {
  // An array element read through a one-key wrapper ({"0": element}) is named as the element,
  // "probes[0]", as every array element is (SpecReader::objects, unknown-key errors).
  const bool index = !key.empty() && key.size() < 10 &&
                     std::all_of(key.begin(), key.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (index && !m_path.empty()) return m_path + "[" + key + "]";
  return m_path.empty() ? key : m_path + "." + key;
}

bool SpecReader::has(const std::string& key) const { return m_node.contains(key); }

const nlohmann::json* SpecReader::find(const std::string& key) const {
  m_read.insert(key);
  auto it = m_node.find(key);
  return it == m_node.end() ? nullptr : &*it;
}

void SpecReader::fail(const std::string& key, const std::string& allowed) const {
  auto it = m_node.find(key);
  throw SpecError(pathOf(key), it == m_node.end() ? "(missing)" : describeValue(*it), allowed);
}

std::vector<SpecReader> SpecReader::objects(const std::string& key, const std::string& what) const {
  std::vector<SpecReader> out;
  const nlohmann::json* v = find(key);
  if (!v) return out;
  if (!v->is_array()) fail(key, "an array of " + what);
  for (std::size_t k = 0; k < v->size(); ++k) {
    const std::string path = pathOf(key) + "[" + std::to_string(k) + "]";
    if (!(*v)[k].is_object()) throw SpecError(path, describeValue((*v)[k]), what);
    out.emplace_back((*v)[k], path);
  }
  return out;
}

SpecReader SpecReader::object(const std::string& key) const {
  const nlohmann::json* v = find(key);
  if (!v || !v->is_object()) fail(key, "a JSON object (required)");
  return SpecReader(*v, pathOf(key));
}

std::optional<SpecReader> SpecReader::optionalObject(const std::string& key) const {
  const nlohmann::json* v = find(key);
  if (!v) return std::nullopt;
  if (!v->is_object()) fail(key, "a JSON object");
  return SpecReader(*v, pathOf(key));
}

double SpecReader::number(const std::string& key, const Range& range, const std::string& unit) const {
  const nlohmann::json* v = find(key);
  const std::string allowed = "a number " + range.describe() + (unit.empty() ? "" : " (" + unit + ")");
  if (!v) fail(key, allowed + ", required");
  if (!v->is_number() || !range.contains(v->get<double>())) fail(key, allowed);
  return v->get<double>();
}

double SpecReader::number(const std::string& key, const Range& range, const std::string& unit,
                          double fallback) const {
  if (!m_node.contains(key)) { m_read.insert(key); return fallback; }
  return number(key, range, unit);
}

std::int64_t SpecReader::integer(const std::string& key, std::int64_t min, std::int64_t max) const {
  const nlohmann::json* v = find(key);
  const std::string allowed = "an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
  if (!v) fail(key, allowed + ", required");
  bool ok = v->is_number_integer();
  if (!ok && v->is_number_float()) {  // accept 3.0, not 3.5
    const double d = v->get<double>();
    ok = std::isfinite(d) && d == std::floor(d) && std::fabs(d) < 9e15;
  }
  if (!ok) fail(key, allowed);
  const auto value = v->is_number_integer() ? v->get<std::int64_t>() : static_cast<std::int64_t>(v->get<double>());
  if (value < min || value > max) fail(key, allowed);
  return value;
}

std::int64_t SpecReader::integer(const std::string& key, std::int64_t min, std::int64_t max,
                                 std::int64_t fallback) const {
  if (!m_node.contains(key)) { m_read.insert(key); return fallback; }
  return integer(key, min, max);
}

bool SpecReader::boolean(const std::string& key, bool fallback) const {
  const nlohmann::json* v = find(key);
  if (!v) return fallback;
  if (!v->is_boolean()) fail(key, "true or false");
  return v->get<bool>();
}

std::string SpecReader::choice(const std::string& key, const std::vector<std::string>& allowed) const {
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + ("\"" + a + "\"");
  const nlohmann::json* v = find(key);
  if (!v) fail(key, "one of " + list + " (required)");
  if (!v->is_string()) fail(key, "one of " + list);
  const std::string s = v->get<std::string>();
  for (const auto& a : allowed)
    if (a == s) return s;
  fail(key, "one of " + list);
}

std::string SpecReader::choice(const std::string& key, const std::vector<std::string>& allowed,
                               const std::string& fallback) const {
  if (!m_node.contains(key)) { m_read.insert(key); return fallback; }
  return choice(key, allowed);
}

std::string SpecReader::string(const std::string& key, const std::string& fallback) const {
  const nlohmann::json* v = find(key);
  if (!v) return fallback;
  if (!v->is_string()) fail(key, "a string");
  return v->get<std::string>();
}

std::vector<double> SpecReader::numbers(const std::string& key, std::size_t minLength, std::size_t maxLength,
                                        const Range& range, const std::string& unit) const {
  const nlohmann::json* v = find(key);
  std::string allowed = "an array of " +
                        (minLength == maxLength ? std::to_string(minLength)
                                                : std::to_string(minLength) + " to " + std::to_string(maxLength)) +
                        " numbers, each " + range.describe() + (unit.empty() ? "" : " (" + unit + ")");
  if (!v) fail(key, allowed + ", required");
  if (!v->is_array() || v->size() < minLength || v->size() > maxLength) fail(key, allowed);
  std::vector<double> out;
  for (const auto& e : *v) {
    if (!e.is_number() || !range.contains(e.get<double>())) fail(key, allowed);
    out.push_back(e.get<double>());
  }
  return out;
}

void SpecReader::finish() const {
  for (auto it = m_node.begin(); it != m_node.end(); ++it)
    if (!m_read.count(it.key()))
      // An empty key would make an empty field name: show it as "" so the message points somewhere.
      throw SpecError(pathOf(it.key().empty() ? "\"\"" : it.key()), describeValue(it.value()),
                      "no such field here (unknown key)");
}

}  // namespace rupture::io
