#include "io/json_text.hpp"

#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include "rupture/spec_error.hpp"

namespace rupture::io {
namespace {

/// nlohmann's DOM builder plus a stack of where we are, so errors can name the field.
template <class Json>
class PathTrackingSax {
public:
  using number_integer_t = typename Json::number_integer_t;
  using number_unsigned_t = typename Json::number_unsigned_t;
  using number_float_t = typename Json::number_float_t;
  using string_t = typename Json::string_t;
  using binary_t = typename Json::binary_t;

  PathTrackingSax(Json& result, std::string_view text) : m_dom(result, true), m_text(text) {}

  bool null() { return value(m_dom.null()); }
  bool boolean(bool v) { return value(m_dom.boolean(v)); }
  bool number_integer(number_integer_t v) { return value(m_dom.number_integer(v)); }
  bool number_unsigned(number_unsigned_t v) { return value(m_dom.number_unsigned(v)); }
  bool number_float(number_float_t v, const string_t& s) { return value(m_dom.number_float(v, s)); }
  bool string(string_t& v) { return value(m_dom.string(v)); }
  bool binary(binary_t& v) { return value(m_dom.binary(v)); }

  bool start_object(std::size_t n) {
    enter(false, n);
    return m_dom.start_object(n);
  }
  bool key(string_t& k) {
    m_stack.back().key = k;
    return m_dom.key(k);
  }
  bool end_object() {
    m_stack.pop_back();
    return value(m_dom.end_object());
  }
  bool start_array(std::size_t n) {
    enter(true, n);
    return m_dom.start_array(n);
  }
  bool end_array() {
    m_stack.pop_back();
    return value(m_dom.end_array());
  }

  bool parse_error(std::size_t position, const std::string& token, const nlohmann::detail::exception& e) {
    if (e.id == 406)  // number overflow: say which field, not just which bytes
      throw JsonLimitError(JsonLimitError::Kind::NumberOutOfRange, position, path(), token.substr(0, 40),
                           "a number within the range of a double (magnitude below 1.8e308)");
    if (e.id == 101) notFiniteLiteral(position);
    // nlohmann's own DOM parser rethrows `e` by its static type (the base class); keep the real one
    // so callers can catch json::parse_error.
    if (const auto* parse = dynamic_cast<const nlohmann::json::parse_error*>(&e)) throw *parse;
    if (const auto* range = dynamic_cast<const nlohmann::json::out_of_range*>(&e)) throw *range;
    return m_dom.parse_error(position, token, e);
  }

private:
  struct Frame {
    bool array = false;
    std::size_t index = 0;
    std::string key;
  };

  /// NaN, Infinity and -Infinity (as JavaScript and Python's json module write them) are not JSON:
  /// say so, with the field and the position, instead of a bare syntax error.
  void notFiniteLiteral(std::size_t position) const {
    // `position` is just past the character that failed: walk back over the word and its sign.
    std::size_t start = std::min(position, m_text.size());
    while (start > 0 && std::isalpha(static_cast<unsigned char>(m_text[start - 1]))) --start;
    if (start > 0 && (m_text[start - 1] == '-' || m_text[start - 1] == '+')) --start;
    std::size_t end = start;
    if (end < m_text.size() && (m_text[end] == '-' || m_text[end] == '+')) ++end;
    while (end < m_text.size() && std::isalpha(static_cast<unsigned char>(m_text[end]))) ++end;
    const std::string word(m_text.substr(start, end - start));
    std::string bare = word.substr(word.empty() || std::isalpha(static_cast<unsigned char>(word[0])) ? 0 : 1);
    for (char& c : bare) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (bare != "nan" && bare != "infinity" && bare != "inf") return;
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i < start; ++i) {
      if (m_text[i] == '\n') { ++line; column = 1; } else { ++column; }
    }
    throw JsonLimitError(JsonLimitError::Kind::NotFinite, start, path(), word,
                         "a finite JSON number (JSON has no NaN or Infinity; '" + word + "' at line " +
                             std::to_string(line) + ", column " + std::to_string(column) + ")");
  }

  void enter(bool array, std::size_t) {
    if (m_stack.size() >= static_cast<std::size_t>(kMaxJsonNesting))
      throw JsonLimitError(JsonLimitError::Kind::TooDeep, 0, path(),
                           "a value nested more than " + std::to_string(kMaxJsonNesting) + " levels deep",
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
  std::string_view m_text;
  std::vector<Frame> m_stack;
};

template <class Json>
Json parseWithPaths(std::string_view text) {
  Json result;
  PathTrackingSax<Json> sax(result, text);
  Json::sax_parse(text.begin(), text.end(), &sax, nlohmann::detail::input_format_t::json, true, false);
  return result;
}

}  // namespace

nlohmann::json parseJsonText(std::string_view text) { return parseWithPaths<nlohmann::json>(text); }

nlohmann::ordered_json parseOrderedJsonText(std::string_view text) {
  return parseWithPaths<nlohmann::ordered_json>(text);
}

}  // namespace rupture::io
