// GET /processes/{id}/previews/{name}: a preview picture a dry run drew (jobs/preview_store.hpp),
// fetched by the submission form's <img> (the page's policy admits images from the server only).
#include <httplib.h>

#include "routes/answers.hpp"
#include "routes/handlers.hpp"
#include "routes/request_params.hpp"

namespace rupture::server {
using httplib::Request;
using httplib::Response;

namespace handlers {

void getProcessPreview(ServerContext& ctx, const Request& req, Response& res) {
  const std::string scenario = req.matches[1], name = req.matches[2];
  if (!knownScenario(scenario)) throw noSuchProcess(scenario);
  refuseUnknownParams(req, {});
  const auto picture = ctx.previews->get(scenario, name);
  if (!picture) {
    throw ApiError(404, problem::kNotFound, "Not Found",
                   "no preview picture '" + name.substr(0, 40) + "' of " + scenario +
                       ": this server keeps the last " + std::to_string(ctx.previews->maxPictures()) +
                       " preview pictures, in memory; ask for the preview again (POST /processes/" + scenario +
                       "/execution?dry_run=true&picture=true)",
                   "name", Json{{"in", "path"}});
  }
  res.set_header("Cache-Control", "private, max-age=600");  // a name is never reused for another picture
  res.set_content(picture->bytes, picture->mediaType);
}

}  // namespace handlers

}  // namespace rupture::server
