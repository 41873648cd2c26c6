#pragma once
// HTML views of the API's own JSON documents (OGC API style: `Accept: text/html` or `?f=html`),
// rendered on the server: no build step, no external assets, every value escaped, and a strict
// Content-Security-Policy whose nonce admits only the page's own inline style and script.
#include <string>

#include "common/problem.hpp"
#include "views/html_page.hpp"

namespace rupture::server {

HtmlPage landingHtml(const Json& landing);
/// The scenarios, each with its inputs (name, unit from "x-unit" when the schema has it, description).
HtmlPage processesHtml(const Json& processes, const Json& schemasByProcess);
/// The job list with its filter form (name, status, scenario); `query` are the current values.
HtmlPage jobsHtml(const Json& jobList, const Json& query, const Json& scenarios);
/// A job: status with live progress (a few lines of inline script poll the JSON), cancel and retry
/// buttons (the token, when the server has one, entered once per browser session), its runs with a
/// thumbnail each, the summary table with units (null until every run has ended), for a replicated
/// job the mean ± 95 % interval per sweep point (`points`: aggregateJson, or null), the plot and
/// the download links.
HtmlPage jobHtml(const Json& status, const Json& summary, const std::string& plotPath, const Json& points = Json());
/// Several jobs side by side (GET /summary?jobs=...&f=html): their rows in one table with a job
/// column and the comparison plot.
HtmlPage comparisonHtml(const Json& comparison, const std::string& plotPath);

/// The page a person gets who pressed Compare with no job ticked (or a choice the server cannot
/// compare, `detail` saying why): what to tick (at most `maxJobs`), and the way back to the job list.
HtmlPage compareChoiceHtml(const std::string& detail, std::size_t maxJobs);

}  // namespace rupture::server
