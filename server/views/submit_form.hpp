#pragma once
// A scenario's page with its submission form (GET /processes/{name}?f=html): one input per field
// of the scenario's JSON Schema (nested objects as fieldsets, units shown, the schema's
// description on hover), filled from a starting spec (the schema's example, or a job's when the
// page is opened from one), the schema's defaults shown in the empty fields but not sent; a sweep (paths and value lists), replicates,
// a name and the token (kept in the browser's session storage, sent as a header, never in a URL).
// A few lines of script build the request and POST it; the server's answer (the job, or the
// problem naming the field) is shown on the page.
#include "views/html_page.hpp"

namespace rupture::server {

/// `process`: the process document (with "inputsSchema"); `start`: the inputs the form starts
/// from (an object; empty: the schema's first example); `request`: the whole body of the job it was
/// opened from (null: none), whose sweep rows, mode, replicates and name fill the job part, and
/// whose members without a field here are sent as they were. The page also previews the job
/// (a dry run: runs, elements, memory, estimated time) before it is submitted.
HtmlPage processHtml(const Json& process, const Json& start, const Json& request = Json());

/// The inputs the form's script posts when the form is submitted as opened (the same arguments):
/// the starting spec's fields that the form has.
Json formInputs(const Json& process, const Json& start);

/// The whole body the script posts when the form opened from `request` (a job's body as posted,
/// with "inputs") is submitted unchanged: a variant keeps the sweep, replicates and name.
Json formRequest(const Json& process, const Json& request);

}  // namespace rupture::server
