#pragma once
// A structural check of the server's HTML pages for tests (no validator is installed offline):
// a doctype, every element closed in order (void elements excepted, script and style read as
// text), attribute values quoted, ids unique, no stray '<' or '&' in text. Returns "" when the
// page passes, else what is wrong and where.
#include <cctype>
#include <set>
#include <string>
#include <vector>

namespace rupture::testing {

inline std::string htmlProblems(const std::string& html) {
  static const std::set<std::string> voids = {"area", "base", "br",    "col",   "embed", "hr",  "img",
                                              "input", "link", "meta", "source", "track", "wbr"};
  auto where = [&](std::size_t at) { return " at byte " + std::to_string(at) + ": " + html.substr(at, 80); };
  if (html.rfind("<!DOCTYPE html>", 0) != 0) return "no <!DOCTYPE html> first";
  std::vector<std::string> open;
  std::set<std::string> ids;
  std::size_t i = html.find('>') + 1;
  while (i < html.size()) {
    const std::size_t lt = html.find('<', i);
    // Text: every '&' starts an entity (&name; or &#...;).
    for (std::size_t a = html.find('&', i); a < std::min(lt, html.size()); a = html.find('&', a + 1)) {
      const std::size_t semi = html.find(';', a);
      if (semi == std::string::npos || semi - a > 10 || semi == a + 1) return "a bare '&' in text" + where(a);
      for (std::size_t k = a + 1; k < semi; ++k)
        if (!std::isalnum(static_cast<unsigned char>(html[k])) && html[k] != '#') return "a bare '&' in text" + where(a);
    }
    if (lt == std::string::npos) break;
    if (html.compare(lt, 4, "<!--") == 0) {
      i = html.find("-->", lt);
      if (i == std::string::npos) return "an unclosed comment" + where(lt);
      i += 3;
      continue;
    }
    const bool closing = lt + 1 < html.size() && html[lt + 1] == '/';
    std::size_t k = lt + (closing ? 2 : 1);
    std::string name;
    while (k < html.size() && (std::isalnum(static_cast<unsigned char>(html[k])) || html[k] == '-'))
      name += static_cast<char>(std::tolower(static_cast<unsigned char>(html[k++])));
    if (name.empty()) return "a '<' that starts no tag" + where(lt);
    // Attributes: name, or name="value" / name='value'.
    while (k < html.size() && html[k] != '>') {
      if (std::isspace(static_cast<unsigned char>(html[k])) || html[k] == '/') {
        ++k;
        continue;
      }
      std::string attribute;
      while (k < html.size() && !std::isspace(static_cast<unsigned char>(html[k])) && html[k] != '=' && html[k] != '>')
        attribute += html[k++];
      if (k < html.size() && html[k] == '=') {
        const char quote = html[++k];
        if (quote != '"' && quote != '\'') return "an unquoted value of " + attribute + where(lt);
        const std::size_t end = html.find(quote, k + 1);
        if (end == std::string::npos) return "an unclosed value of " + attribute + where(lt);
        const std::string value = html.substr(k + 1, end - k - 1);
        if (value.find('<') != std::string::npos) return "a '<' in the value of " + attribute + where(lt);
        if (attribute == "id" && !closing && !ids.insert(value).second) return "the id '" + value + "' twice" + where(lt);
        k = end + 1;
      }
    }
    if (k >= html.size()) return "an unclosed tag" + where(lt);
    i = k + 1;
    if (closing) {
      if (open.empty() || open.back() != name)
        return "</" + name + "> closes " + (open.empty() ? std::string("nothing") : "<" + open.back() + ">") + where(lt);
      open.pop_back();
    } else if (name == "script" || name == "style") {
      const std::size_t end = html.find("</" + name + ">", i);
      if (end == std::string::npos) return "an unclosed <" + name + ">" + where(lt);
      i = end + name.size() + 3;
    } else if (!voids.count(name) && html[k - 1] != '/') {
      open.push_back(name);
    }
  }
  if (!open.empty()) return "<" + open.back() + "> is never closed";
  return "";
}

}  // namespace rupture::testing
