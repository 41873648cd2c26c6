#include "json_body.hpp"

#include <algorithm>
#include <vector>

#include "utf8.hpp"

namespace rupture::server {
namespace {

/// Deepest nesting of arrays and objects in a JSON text (strings skipped). Checked before parsing:
/// nlohmann::json parses, copies and frees nested values recursively, so a body of half a million
/// '[' would overflow the stack.
int jsonNestingDepth(const std::string& text) {
  int depth = 0, deepest = 0;
  bool inString = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\') ++i;
      else if (c == '"') inString = false;
      continue;
    }
    if (c == '"') inString = true;
    else if (c == '[' || c == '{') deepest = std::max(deepest, ++depth);
    else if (c == ']' || c == '}') --depth;
  }
  return deepest;
}

/// Builds the document like nlohmann's own DOM parser, but knows the path of the value being read,
/// so that an error (a number overflow) can name its field.
class PathTrackingBuilder {
public:
  using number_integer_t = Json::number_integer_t;
  using number_unsigned_t = Json::number_unsigned_t;
  using number_float_t = Json::number_float_t;
  using string_t = Json::string_t;
  using binary_t = Json::binary_t;

  explicit PathTrackingBuilder(Json& root) : m_root(root) {}

  bool null() { return place(Json(nullptr)) != nullptr; }
  bool boolean(bool v) { return place(Json(v)) != nullptr; }
  bool number_integer(number_integer_t v) { return place(Json(v)) != nullptr; }
  bool number_unsigned(number_unsigned_t v) { return place(Json(v)) != nullptr; }
  bool number_float(number_float_t v, const string_t&) { return place(Json(v)) != nullptr; }
  bool string(string_t& v) { return place(Json(std::move(v))) != nullptr; }
  bool binary(binary_t& v) { return place(Json::binary(std::move(v))) != nullptr; }
  bool start_object(std::size_t) {
    m_stack.push_back({place(Json::object()), {}});
    return true;
  }
  bool key(string_t& k) {
    m_stack.back().key = k;
    return true;
  }
  bool end_object() {
    m_stack.pop_back();
    return true;
  }
  bool start_array(std::size_t) {
    m_stack.push_back({place(Json::array()), {}});
    return true;
  }
  bool end_array() {
    m_stack.pop_back();
    return true;
  }
  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& ex) {
    m_errorId = ex.id;
    m_errorByte = position;
    m_errorText = ex.what();
    m_errorPath = currentPath();
    return false;
  }

  int errorId() const { return m_errorId; }
  std::size_t errorByte() const { return m_errorByte; }
  const std::string& errorText() const { return m_errorText; }
  const std::string& errorPath() const { return m_errorPath; }

private:
  struct Frame {
    Json* container;  // stays valid: its parent grows only after this frame is closed
    std::string key;
  };

  Json* place(Json value) {
    if (m_stack.empty()) {
      m_root = std::move(value);
      return &m_root;
    }
    Frame& top = m_stack.back();
    if (top.container->is_object()) {
      Json& slot = (*top.container)[top.key];  // a repeated key: the last one wins, as in Json::parse
      slot = std::move(value);
      return &slot;
    }
    top.container->push_back(std::move(value));
    return &top.container->back();
  }

  std::string currentPath() const {
    std::string path;
    for (const Frame& f : m_stack) {
      if (f.container->is_object()) {
        if (!path.empty()) path += '.';
        path += f.key;
      } else {
        path += '[';
        path += std::to_string(f.container->size());
        path += ']';
      }
    }
    return path;
  }

  Json& m_root;
  std::vector<Frame> m_stack;
  int m_errorId = 0;
  std::size_t m_errorByte = 0;
  std::string m_errorText;
  std::string m_errorPath;
};

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
  if (jsonNestingDepth(body) > kMaxJsonDepth) {
    throw invalidJson("the request body nests arrays or objects deeper than " + std::to_string(kMaxJsonDepth) +
                          " levels",
                      Json::object());
  }
  Json doc;
  PathTrackingBuilder builder(doc);
  const bool ok = Json::sax_parse(body.begin(), body.end(), &builder, nlohmann::json::input_format_t::json, true);
  if (ok) return doc;
  const std::string& path = builder.errorPath();
  if (builder.errorId() == 406) {  // out_of_range.406: a number overflows a double
    const bool inInputs = path.rfind("inputs.", 0) == 0;
    const std::string field = inInputs ? path.substr(7) : path;
    throw ApiError(400, problem::kInvalidJson, "Invalid JSON",
                   "the number at '" + (path.empty() ? std::string("(root)") : path) +
                       "' is outside the range of a double (about 1.8e308); numbers must be finite",
                   field, Json{{"in", inInputs ? "inputs" : "body"}, {"byte", builder.errorByte()}});
  }
  // The parser's message quotes the bytes it last read: keep it UTF-8 and short.
  throw invalidJson("the request body is not valid JSON: " + truncateUtf8(builder.errorText(), 300),
                    Json{{"byte", builder.errorByte()}});
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
