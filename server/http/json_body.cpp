#include "http/json_body.hpp"

#include <algorithm>
#include <vector>

#include "io/json_text.hpp"
#include "common/utf8.hpp"

namespace rupture::server {
namespace {

ApiError invalidJson(const std::string& detail, Json extra) {
  extra["in"] = "body";
  return ApiError(400, problem::kInvalidJson, "Invalid JSON", detail, "", std::move(extra));
}

}  // namespace

Json parseJsonBody(const std::string& body) {
  if (body.empty()) {
    throw invalidJson("the request body is empty; send {\"inputs\": {...}} with Content-Type: application/json",
                      Json::object());
  }
  if (const std::size_t nul = body.find('\0'); nul != std::string::npos) {
    throw invalidJson("the request body holds a NUL byte at byte " + std::to_string(nul) +
                          "; JSON text cannot contain one",
                      Json{{"byte", nul}});
  }
  if (const std::size_t bad = firstInvalidUtf8(body); bad != std::string::npos) {
    throw invalidJson("the request body is not valid UTF-8 (ill-formed byte sequence at byte " + std::to_string(bad) +
                          ")",
                      Json{{"byte", bad}});
  }
  // The one spec reader (engine/io/json_text.hpp) names the field of a number out of range and
  // stops nesting before it can overflow a recursive copy.
  try {
    return rupture::io::parseOrderedJsonText(body);
  } catch (const rupture::io::JsonLimitError& e) {
    if (e.kind() == rupture::io::JsonLimitError::Kind::TooDeep)
      throw invalidJson("the request body nests arrays or objects deeper than " + std::to_string(kMaxJsonDepth) +
                            " levels",
                        Json::object());
    const std::string& path = e.field();
    const bool inInputs = path.rfind("inputs.", 0) == 0;
    const std::string field = inInputs ? path.substr(7) : path;
    if (e.kind() == rupture::io::JsonLimitError::Kind::NotFinite)
      throw ApiError(400, problem::kInvalidJson, "Invalid JSON",
                     "the value '" + truncateUtf8(e.value(), 40) + "' at '" + path + "' (byte " + std::to_string(e.byte()) +
                         ") is not JSON: JSON has no NaN or Infinity numbers; send a finite number, or leave the field out for its default",
                     field, Json{{"in", inInputs ? "inputs" : "body"}, {"byte", e.byte()}, {"value", truncateUtf8(e.value(), 40)}, {"allowed", e.allowed()}});
    throw ApiError(400, problem::kInvalidJson, "Invalid JSON",
                   "the number at '" + path + "' is outside the range of a double (about 1.8e308); numbers must be finite",
                   field, Json{{"in", inInputs ? "inputs" : "body"}, {"byte", e.byte()}});
  } catch (const nlohmann::json::parse_error& e) {
    // The parser's message quotes the bytes it last read: keep it UTF-8 and short.
    throw invalidJson("the request body is not valid JSON: " + truncateUtf8(e.what(), 300), Json{{"byte", e.byte}});
  }
}

std::string findEmptyKey(const Json& value, const std::string& path) {
  if (value.is_object()) {
    for (const auto& [key, child] : value.items()) {
      if (key.empty()) return path.empty() ? std::string("\"\"") : path + ".\"\"";
      const std::string childPath = path.empty() ? key : path + "." + key;
      if (std::string found = findEmptyKey(child, childPath); !found.empty()) return found;
    }
  } else if (value.is_array()) {
    for (std::size_t i = 0; i < value.size(); ++i) {
      std::string childPath = path;
      childPath += '[';
      childPath += std::to_string(i);
      childPath += ']';
      if (std::string found = findEmptyKey(value[i], childPath); !found.empty()) return found;
    }
  }
  return "";
}

}  // namespace rupture::server
