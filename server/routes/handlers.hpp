#pragma once
// Every request handler, one per method and path; routes.cpp's table binds them to paths.
// A handler throws ApiError (or SpecError) for the client's mistakes; the boundary answers.
#include <httplib.h>

#include "routes/server_context.hpp"

namespace rupture::server::handlers {

using Handler = void (*)(ServerContext&, const httplib::Request&, httplib::Response&);

// service_handlers.cpp
void getLanding(ServerContext&, const httplib::Request&, httplib::Response&);
void getHealth(ServerContext&, const httplib::Request&, httplib::Response&);
void getOpenApi(ServerContext&, const httplib::Request&, httplib::Response&);
void getConformance(ServerContext&, const httplib::Request&, httplib::Response&);
// process_handlers.cpp
void getProcesses(ServerContext&, const httplib::Request&, httplib::Response&);
void getProcess(ServerContext&, const httplib::Request&, httplib::Response&);
void getProcessPreview(ServerContext&, const httplib::Request&, httplib::Response&);
void postExecution(ServerContext&, const httplib::Request&, httplib::Response&);
// job_handlers.cpp
void getJobs(ServerContext&, const httplib::Request&, httplib::Response&);
void getJob(ServerContext&, const httplib::Request&, httplib::Response&);
void deleteJob(ServerContext&, const httplib::Request&, httplib::Response&);
void postRetry(ServerContext&, const httplib::Request&, httplib::Response&);
void postResume(ServerContext&, const httplib::Request&, httplib::Response&);
void getRuns(ServerContext&, const httplib::Request&, httplib::Response&);
void getRun(ServerContext&, const httplib::Request&, httplib::Response&);
// result_handlers.cpp
void getJobResults(ServerContext&, const httplib::Request&, httplib::Response&);
void getJobCrate(ServerContext&, const httplib::Request&, httplib::Response&);
void getJobReport(ServerContext&, const httplib::Request&, httplib::Response&);
void getRunResults(ServerContext&, const httplib::Request&, httplib::Response&);
void getRunSeries(ServerContext&, const httplib::Request&, httplib::Response&);
void getRunXdmf(ServerContext&, const httplib::Request&, httplib::Response&);
void getRunBundle(ServerContext&, const httplib::Request&, httplib::Response&);
// picture_handlers.cpp
void getRunField(ServerContext&, const httplib::Request&, httplib::Response&);
/// GET .../series with format=svg|png|pdf (getRunSeries hands it over).
void getRunSeriesPlot(ServerContext&, const httplib::Request&, httplib::Response&);
// summary_handlers.cpp
void getJobSummary(ServerContext&, const httplib::Request&, httplib::Response&);
void getJobSummaryPlot(ServerContext&, const httplib::Request&, httplib::Response&);
void getComparedSummary(ServerContext&, const httplib::Request&, httplib::Response&);
void getComparedPlot(ServerContext&, const httplib::Request&, httplib::Response&);

}  // namespace rupture::server::handlers
