#include "jobs/replicates.hpp"

#include <functional>

#include "rupture/run.hpp"

namespace rupture::server {
namespace {

ApiError replicateError(const std::string& field, const Json& value, const std::string& detail, const Json& allowed) {
  Json extra{{"in", "body"}, {"value", value}};
  if (!allowed.is_null()) extra["allowed"] = allowed;
  return ApiError(400, problem::kInvalidRequest, "Invalid replicates", detail, field, extra);
}

/// Every integer field of a schema, as dotted paths (for the error that lists what is allowed).
void integerFields(const nlohmann::json& node, const std::string& prefix, Json& out) {
  if (prefix.size() && isIntegerSchema(node)) out.push_back(prefix);
  if (node.contains("properties") && node["properties"].is_object()) {
    for (const auto& [key, sub] : node["properties"].items()) {
      integerFields(sub, prefix.empty() ? key : prefix + "." + key, out);
    }
  }
}

nlohmann::json schemaOf(const std::string& scenario) {
  try {
    return rupture::scenarioSchema(scenario);
  } catch (const std::exception&) {
    return nlohmann::json::object();
  }
}

}  // namespace

const nlohmann::json* schemaNodeAt(const nlohmann::json& schema, const std::string& path) {
  const nlohmann::json* node = &schema;
  const auto segments = splitPath(path);
  if (segments.empty()) return nullptr;
  for (const std::string& segment : segments) {
    if (node->contains("properties") && (*node)["properties"].contains(segment)) {
      node = &(*node)["properties"][segment];
    } else if (node->contains("items") && (*node)["items"].is_object()) {
      node = &(*node)["items"];
    } else {
      return nullptr;
    }
  }
  return node;
}

bool isIntegerSchema(const nlohmann::json& node) {
  if (!node.contains("type")) return false;
  const auto& type = node["type"];
  if (type.is_string()) return type == "integer";
  if (type.is_array()) {
    for (const auto& t : type) {
      if (t == "integer") return true;
    }
  }
  return false;
}

ReplicatePlan parseReplicatePlan(const Json* member, const std::string& scenario, const SweepPlan& sweep) {
  ReplicatePlan plan;
  if (!member || member->is_null()) return plan;
  if (!member->is_object()) {
    throw replicateError("replicates", *member,
                         "replicates must be an object such as {\"count\": 5, \"vary\": \"sample.seed\"}", Json());
  }
  for (const auto& [key, value] : member->items()) {
    if (key != "count" && key != "vary") {
      throw replicateError("replicates." + key, value, "unknown member '" + key + "' in replicates; allowed: count, vary",
                           Json::array({"count", "vary"}));
    }
  }
  const auto count = member->find("count");
  if (count == member->end() || !count->is_number_integer() || count->get<long long>() < 1 ||
      count->get<long long>() > kMaxReplicates) {
    const Json value = count == member->end() ? Json("(missing)") : *count;
    throw replicateError("replicates.count", value,
                         "replicates.count must be an integer from 1 to " + std::to_string(kMaxReplicates) +
                             " (samples per sweep point), got " + value.dump(),
                         Json{{"minimum", 1}, {"maximum", kMaxReplicates}});
  }
  plan.count = count->get<int>();
  const nlohmann::json schema = schemaOf(scenario);
  Json allowed = Json::array();
  integerFields(schema, "", allowed);
  const auto vary = member->find("vary");
  if (vary == member->end() || !vary->is_string()) {
    const Json value = vary == member->end() ? Json("(missing)") : *vary;
    throw replicateError("replicates.vary", value,
                         "replicates.vary must name the integer spec field the replicates vary (e.g. \"sample.seed\"), got " +
                             value.dump(),
                         allowed);
  }
  plan.vary = vary->get<std::string>();
  const nlohmann::json* node = schemaNodeAt(schema, plan.vary);
  if (!node || !isIntegerSchema(*node)) {
    throw replicateError("replicates.vary", *vary,
                         "replicates.vary '" + plan.vary + "' is not an integer field of the " + scenario +
                             " schema; integer fields: " + allowed.dump(),
                         allowed);
  }
  for (const SweepAxis& axis : sweep.axes) {
    if (axis.path == plan.vary || axis.path.rfind(plan.vary + ".", 0) == 0 || plan.vary.rfind(axis.path + ".", 0) == 0) {
      throw replicateError("replicates.vary", *vary,
                           "replicates.vary '" + plan.vary + "' is also swept; replicates vary a field the sweep leaves alone",
                           allowed);
    }
  }
  return plan;
}

ReplicateExpander::ReplicateExpander(const ReplicatePlan& plan, const std::string& scenario) : m_plan(plan) {
  if (!plan.requested()) return;
  const nlohmann::json schema = schemaOf(scenario);
  if (const nlohmann::json* node = schemaNodeAt(schema, plan.vary);
      node && node->contains("default") && (*node)["default"].is_number_integer())
    m_default = (*node)["default"];
  m_segments = splitPath(plan.vary);
}

void ReplicateExpander::expand(SweepPoint&& p, const std::function<void(ReplicatedPoint&&)>& visit) const {
  if (!m_plan.requested()) {
    visit({std::move(p), 0});  // specs can be large: no copies
    return;
  }
  long long base = 0;
  if (const Json* v = findAtPath(p.spec, m_plan.vary); v && v->is_number_integer()) {
    base = v->get<long long>();
  } else if (v) {
    throw replicateError("replicates.vary", m_plan.vary,
                         "the inputs set " + m_plan.vary + " to " + v->dump() + ", not an integer; replicates add 0.." +
                             std::to_string(m_plan.count - 1) + " to it",
                         Json());
  } else if (!m_default.is_null()) {
    base = m_default.get<long long>();
  } else {
    throw replicateError("replicates.vary", m_plan.vary,
                         m_plan.vary + " has no value in the inputs and no default in the schema; set it in the inputs",
                         Json());
  }
  for (int r = 0; r < m_plan.count; ++r) {
    ReplicatedPoint rp{r + 1 < m_plan.count ? p : std::move(p), r};
    // Walk to the parent, creating objects (the field may be absent and defaulted).
    Json* parent = &rp.point.spec;
    for (std::size_t i = 0; i + 1 < m_segments.size(); ++i) {
      if (!parent->is_object()) break;
      parent = &(*parent)[m_segments[i]];
      if (parent->is_null()) *parent = Json::object();
    }
    if (!parent->is_object()) {
      throw replicateError("replicates.vary", m_plan.vary, "the inputs hold no object at the parent of " + m_plan.vary,
                           Json());
    }
    (*parent)[m_segments.back()] = base + r;
    visit(std::move(rp));
  }
}

std::vector<ReplicatedPoint> expandReplicates(std::vector<SweepPoint> points, const ReplicatePlan& plan,
                                              const std::string& scenario) {
  std::vector<ReplicatedPoint> out;
  out.reserve(points.size() * static_cast<std::size_t>(plan.requested() ? plan.count : 1));
  const ReplicateExpander expander(plan, scenario);
  for (SweepPoint& p : points) expander.expand(std::move(p), [&](ReplicatedPoint&& rp) { out.push_back(std::move(rp)); });
  return out;
}

}  // namespace rupture::server
