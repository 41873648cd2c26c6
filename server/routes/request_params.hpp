#pragma once
// What handlers read from a request: path ids, query parameters, content negotiation and the
// token, each failing with a problem that names the parameter; and the job or run a path names.
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include <httplib.h>

#include "jobs/job_store.hpp"
#include "routes/server_context.hpp"
#include "views/svg_plot.hpp"

namespace rupture::server {

/// Strict non-negative integer parse (digits only, no sign, no spaces, fits in int64).
std::optional<std::int64_t> parseIndex(const std::string& text);

ApiError noSuchJob(const std::string& id);
ApiError noSuchProcess(const std::string& name);
bool knownScenario(const std::string& name);

std::int64_t jobIdFrom(const httplib::Request& req);
int runIndexFrom(const httplib::Request& req, const JobRecord& job);

/// ?name= as one of `allowed` (nullopt when absent); a 400 naming the allowed values otherwise.
std::optional<std::string> choiceParam(const httplib::Request& req, const char* name,
                                       std::initializer_list<const char*> allowed);
/// ?format=csv|json, else the Accept header.
bool wantsCsv(const httplib::Request& req);
/// OGC API style: ?f=html, or a browser's Accept (text/html) when ?f is absent; ?f=json is JSON.
bool wantsHtml(const httplib::Request& req);

/// Every query parameter is one of `known`; else a 400 naming it and listing them (an option is
/// honoured or refused, never ignored).
void refuseUnknownParams(const httplib::Request& req, const std::vector<std::string>& known);

std::vector<std::string> splitList(const std::string& text);
/// Every value of a (possibly repeated) query parameter, comma lists split.
std::vector<std::string> paramList(const httplib::Request& req, const std::string& name);
std::int64_t intParam(const httplib::Request& req, const char* name, std::int64_t fallback, std::int64_t lo,
                      std::int64_t hi);
std::optional<double> numberParam(const httplib::Request& req, const char* name);
AxisScale scaleParam(const httplib::Request& req, const char* name);
/// ?aggregate=replicates (statistics per sweep point) or ?aggregate=none (the runs; default).
bool aggregateParam(const httplib::Request& req);

/// POST and DELETE need the bearer token when the server has one (--token).
void requireToken(const ServerContext& ctx, const httplib::Request& req);

JobRecord loadJob(ServerContext& ctx, const httplib::Request& req);
/// loadJob with the job's runs, read together (JobStore::jobWithRuns).
JobWithRuns loadJobWithRuns(ServerContext& ctx, const httplib::Request& req);
RunRecord loadRun(ServerContext& ctx, const httplib::Request& req, const JobRecord& job);
/// The run, which must be successful with its file in place.
RunRecord finishedRun(ServerContext& ctx, const httplib::Request& req, const JobRecord& job);

}  // namespace rupture::server
