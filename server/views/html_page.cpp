#include "views/html_page.hpp"

#include <random>

#include "io/xml_escape.hpp"
#include "rupture/quantity_text.hpp"

namespace rupture::server {

using rupture::io::xmlEscape;

namespace {

std::string newNonce() {
  static thread_local std::mt19937_64 engine{std::random_device{}()};
  static const char* digits = "0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ";
  std::string out;
  for (int i = 0; i < 22; ++i) out += digits[engine() % 62];
  return out;
}

}  // namespace

std::string HtmlPage::csp() const {
  return "default-src 'none'; img-src 'self'; connect-src 'self'; style-src 'nonce-" + nonce +
         "'; script-src 'nonce-" + nonce + "'; base-uri 'none'; form-action 'self'; frame-ancestors 'none'";
}

namespace html {

std::string esc(const Json& v) {
  if (v.is_string()) return xmlEscape(v.get<std::string>());
  if (v.is_null()) return "";
  return xmlEscape(v.dump());
}

std::string href(const std::string& path) { return xmlEscape(path); }

/// The page frame: one inline style, navigation, the content, and an optional inline script.
HtmlPage page(const std::string& title, const std::string& content, const std::string& script) {
  HtmlPage p;
  p.nonce = newNonce();
  p.body = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
           "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
           "<title>" + xmlEscape(title) + " - Rupture</title>"
           "<style nonce=\"" + p.nonce + "\">"
           "body{font-family:system-ui,sans-serif;margin:1.5em auto;max-width:72em;padding:0 1em;color:#222}"
           "table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ccc;padding:.25em .5em;text-align:left}"
           "th{background:#f3f3f3}td.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}"
           "nav a{margin-right:1em}progress{width:16em}.unit{color:#666;font-weight:normal}"
           "img{max-width:100%;border:1px solid #ddd}.error{color:#a40000}</style></head><body>"
           "<nav><a href=\"/?f=html\">Rupture</a><a href=\"/processes?f=html\">Scenarios</a>"
           "<a href=\"/jobs?f=html\">Jobs</a><a href=\"/openapi.yaml\">API</a></nav>\n<h1>" +
           xmlEscape(title) + "</h1>\n" + content;
  if (!script.empty()) p.body += "<script nonce=\"" + p.nonce + "\">" + script + "</script>";
  p.body += "</body></html>\n";
  return p;
}

std::string cell(const Json& v) {
  const bool number = v.is_number();
  return std::string(number ? "<td class=\"num\">" : "<td>") + esc(v) + "</td>";
}

/// A table cell for a value in `unit`: a number as people read it (rupture::formatQuantity), its
/// full precision in the title; anything else as cell() writes it.
std::string quantityCell(const Json& v, const std::string& unit) {
  if (!v.is_number()) return cell(v);
  return "<td class=\"num\" title=\"" + esc(v) + "\">" + xmlEscape(rupture::formatQuantity(v.get<double>(), unit)) + "</td>";
}

}  // namespace html
}  // namespace rupture::server
