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
/// A complete document made elsewhere (the validation report of engine/validation) served like
/// the server's own pages: its `<style>` elements get the page's nonce; no script is admitted.
HtmlPage document(std::string html);
/// A table cell; numbers right-aligned, booleans as yes/no, an empty value as a dash whose title
/// says why (`whyEmpty`, e.g. "not measured", "run failed").
std::string cell(const Json& v, const std::string& whyEmpty = "no value");
/// A table cell for a value in `unit`: a number as people read it (rupture::formatQuantity), its
/// full precision in the title; a flag (see isFlag) as yes/no; anything else as cell() writes it.
std::string quantityCell(const Json& v, const std::string& unit, const std::string& whyEmpty = "no value",
                         bool flag = false);
/// Whether a declared column or field (name, unit, description) is a yes/no flag stored as 1/0:
/// dimensionless, described as "1 when ..." or "1 if ..." (separated, completed).
bool isFlag(const Json& column);
/// Why a row's cell is empty, from its run's status: "run failed", "run cancelled", "not finished
/// yet", else "not measured by this run".
std::string whyEmpty(const Json& row);
/// The script functions a page's live updates write numbers with, as rupture::formatQuantity and
/// rupture::roundNumbersInText do on the server: fq(value, unit) for seconds ("s") and
/// dimensionless values (""), r3(text) for a stage's long decimals.
const std::string& numberScript();
/// An ETA cell's text: the time as people read it, or "unknown" (a job running without a
/// measured rate) or "—" (an ended job), with a title saying why.
std::string etaText(const Json& etaSeconds, bool active);
/// A table that may be wider than the page: it scrolls inside a wrapper, its first column stays.
std::string scrolling(const std::string& table);

/// A summary document (`summaryJson`, `comparisonJson`; columns with name, unit, label, kind) as
/// a table a laptop shows: the declared labels as headers (the key on hover), values with their unit
/// and three significant digits (the full value on hover), the leading job/run/status/replicate
/// columns the rows have, the swept inputs and the first `shownResults` results; when there are more,
/// every column one click away in a second table (id + "-all").
std::string summaryTable(const Json& summary, const std::string& id, std::size_t shownResults = 8);

/// A schema node's SI unit (keyword "x-unit"), "" when it has none.
std::string schemaUnit(const Json& node);
/// Table rows (field, type, unit, description) of a schema's inputs, dotted paths for nested
/// objects, appended to `out`.
void inputRows(const Json& schema, const std::string& prefix, std::string& out, int depth = 0);

}  // namespace html
}  // namespace rupture::server
