#pragma once
// A run's page (GET /jobs/{id}/runs/{k}?f=html): its status and swept values (the reason when it
// failed), the picture of its field at a chosen snapshot with a strip of pictures over time, plots
// of its series, its summary with labels and engineering units, its spec and its files.
#include <filesystem>

#include "rupture/run.hpp"
#include "views/html_page.hpp"

namespace rupture::server {

/// `data`: {"job": {jobID, name, processID}, "run": the run document with "spec",
/// "pictures": {"fields": [...], "snapshots": [{index, time, strain}], "series": [{name, label}],
/// "x": "strain"} (absent without a result file), "summary_fields": [{name, label, unit}],
/// "chosen": {field, snapshot, view, bonds}, "provenance": runProvenance's (absent without a file)}.
HtmlPage runHtml(const Json& data);

/// The "pictures" member of runHtml's data from a finished run's file: the fields and snapshots
/// it can show and the declared series it holds (up to eight, each against strain when recorded,
/// else time). Empty members when the file holds none.
Json runPictures(const std::filesystem::path& file, const ScenarioInfo* scenario);

/// The "provenance" member of runHtml's data: the run file's /provenance attributes (docs/provenance.md),
/// an empty object for a file written before they were recorded.
Json runProvenance(const std::filesystem::path& file);

}  // namespace rupture::server
