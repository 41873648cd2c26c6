#pragma once
// The parts every HTML view is made of: the page frame (one inline style and script admitted by a
// per-page CSP nonce, navigation), escaping, and table cells that show quantities as people read
// them (58.4 MPa) with the full value on hover.
#include <string>

#include "common/problem.hpp"

namespace rupture::server {

/// A page and the nonce its CSP header must carry.
struct HtmlPage {
  std::string body;
  std::string nonce;
  std::string csp() const;
};

namespace html {

/// A JSON value as escaped text (strings without quotes, null as nothing).
std::string esc(const Json& v);
/// A path for an href or src attribute, escaped.
std::string href(const std::string& path);
/// The page frame around `content`; `script` (optional) runs under the page's nonce.
HtmlPage page(const std::string& title, const std::string& content, const std::string& script = {});
/// A table cell; numbers right-aligned.
std::string cell(const Json& v);
/// A table cell for a value in `unit`: a number as people read it (rupture::formatQuantity), its
/// full precision in the title; anything else as cell() writes it.
std::string quantityCell(const Json& v, const std::string& unit);

}  // namespace html
}  // namespace rupture::server
