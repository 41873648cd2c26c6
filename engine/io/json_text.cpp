#include "io/json_text.hpp"

#include <string>
#include <vector>

#include "rupture/spec_error.hpp"

namespace rupture::io {
namespace {

using Json = nlohmann::json;

/// nlohmann's DOM builder plus a stack of where we are, so errors can name the field.
class PathTrackingSax {
public:
  explicit PathTrackingSax(Json& result) : m_dom(result, true) {}

  bool null() { return value(m_dom.null()); }
  bool boolean(bool v) { return value(m_dom.boolean(v)); }
  bool number_integer(Json::number_integer_t v) { return value(m_dom.number_integer(v)); }
  bool number_unsigned(Json::number_unsigned_t v) { return value(m_dom.number_unsigned(v)); }
  bool number_float(Json::number_float_t v, const Json::string_t& s) { return value(m_dom.number_float(v, s)); }
  bool string(Json::string_t& v) { return value(m_dom.string(v)); }
  bool binary(Json::binary_t& v) { return value(m_dom.binary(v)); }

  bool start_object(std::size_t n) {
    enter(false);
    return m_dom.start_object(n);
  }
  bool key(Json::string_t& k) {
    m_stack.back().key = k;
    return m_dom.key(k);
  }
  bool end_object() {
    m_stack.pop_back();
    return value(m_dom.end_object());
  }
  bool start_array(std::size_t n) {
    enter(true);
    return m_dom.start_array(n);
  }
  bool end_array() {
    m_stack.pop_back();
    return value(m_dom.end_array());
  }

  bool parse_error(std::size_t position, const std::string& token, const nlohmann::detail::exception& e) {
    if (e.id == 406)  // number overflow: say which field, not just which bytes
      throw SpecError(path(), token.substr(0, 40), "a number within the range of a double (magnitude below 1.8e308)");
    // nlohmann's own DOM parser rethrows `e` by its static type (the base class); keep the real one
    // so callers can catch json::parse_error.
    (void)position;
    if (const auto* parse = dynamic_cast<const Json::parse_error*>(&e)) throw *parse;
    if (const auto* range = dynamic_cast<const Json::out_of_range*>(&e)) throw *range;
    return m_dom.parse_error(position, token, e);
  }

private:
  struct Frame {
    bool array = false;
    std::size_t index = 0;
    std::string key;
  };

  void enter(bool array) {
    if (m_stack.size() >= static_cast<std::size_t>(kMaxJsonNesting))
      throw SpecError(path(), "a value nested more than " + std::to_string(kMaxJsonNesting) + " levels deep",
                      "at most " + std::to_string(kMaxJsonNesting) + " levels of nested arrays and objects");
    m_stack.push_back({array, 0, {}});
  }
  /// A complete value was read: the next one in an array has the next index.
  bool value(bool ok) {
    if (!m_stack.empty() && m_stack.back().array) ++m_stack.back().index;
    return ok;
  }
  std::string path() const {
    std::string out;
    for (const Frame& f : m_stack) {
      if (f.array) out += "[" + std::to_string(f.index) + "]";
      else if (!f.key.empty() || !out.empty()) out += (out.empty() ? "" : ".") + f.key;
    }
    return out.empty() ? "(root)" : out;
  }

  nlohmann::detail::json_sax_dom_parser<Json> m_dom;
  std::vector<Frame> m_stack;
};

}  // namespace

Json parseJsonText(std::string_view text) {
  Json result;
  PathTrackingSax sax(result);
  Json::sax_parse(text.begin(), text.end(), &sax, nlohmann::detail::input_format_t::json, true, false);
  return result;
}

}  // namespace rupture::io
