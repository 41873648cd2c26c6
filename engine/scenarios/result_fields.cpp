#include "rupture/result_fields.hpp"

#include <cctype>

namespace rupture {
namespace {

/// The schema node of a dotted spec path (through "properties", and "items" for arrays), or null.
const nlohmann::json* schemaNode(const nlohmann::json& schema, const std::string& dottedPath) {
  const nlohmann::json* node = &schema;
  std::size_t start = 0;
  while (start <= dottedPath.size()) {
    const std::size_t dot = dottedPath.find('.', start);
    const std::string segment = dottedPath.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (node->contains("properties") && (*node)["properties"].contains(segment)) {
      node = &(*node)["properties"][segment];
    } else if (node->contains("items") && !segment.empty() && std::isdigit(static_cast<unsigned char>(segment[0]))) {
      node = &(*node)["items"];
    } else {
      return nullptr;
    }
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  // An array of numbers carries its unit on the array or on its items.
  if (!node->contains("x-unit") && node->contains("items") && (*node)["items"].is_object() &&
      (*node)["items"].contains("x-unit"))
    return &(*node)["items"];
  return node;
}

}  // namespace

const ResultField* findResultField(const ResultFields& fields, const std::string& name) {
  for (const ResultField& f : fields)
    if (f.name == name) return &f;
  for (const ResultField& f : fields)
    if (!f.name.empty() && f.name.back() == '*' && name.size() >= f.name.size() &&
        name.compare(0, f.name.size() - 1, f.name, 0, f.name.size() - 1) == 0)
      return &f;
  return nullptr;
}

std::map<std::string, std::string> unitMap(const ResultFields& fields, int dimension) {
  std::map<std::string, std::string> units;
  for (const ResultField& f : fields)
    if (f.name.empty() || f.name.back() != '*') units[f.name] = f.unitFor(dimension);
  return units;
}

int specDimension(const nlohmann::json& schema, const nlohmann::json& spec) {
  if (spec.is_object()) {
    auto it = spec.find("dimension");
    if (it != spec.end() && it->is_number_integer()) return it->get<int>();
  }
  const nlohmann::json* node = schemaNode(schema, "dimension");
  if (node && node->contains("default") && (*node)["default"].is_number_integer()) return (*node)["default"].get<int>();
  return 3;
}

std::string specFieldUnit(const nlohmann::json& schema, const std::string& dottedPath) {
  const nlohmann::json* node = schemaNode(schema, dottedPath);
  if (!node) return "";
  auto it = node->find("x-unit");
  return it != node->end() && it->is_string() ? it->get<std::string>() : "";
}

std::string specFieldLabel(const nlohmann::json& schema, const std::string& dottedPath) {
  if (const nlohmann::json* node = schemaNode(schema, dottedPath)) {
    auto it = node->find("title");
    if (it != node->end() && it->is_string()) return it->get<std::string>();
  }
  std::string label = dottedPath.substr(dottedPath.rfind('.') == std::string::npos ? 0 : dottedPath.rfind('.') + 1);
  for (char& c : label)
    if (c == '_') c = ' ';
  if (!label.empty()) label[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(label[0])));
  return label;
}

std::string nameWithUnit(const std::string& name, const std::string& unit) {
  return unit.empty() ? name : name + " [" + unit + "]";
}

}  // namespace rupture
