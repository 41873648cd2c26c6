#include "common/problem.hpp"

namespace rupture::server {

const char* statusTitle(int status) {
  switch (status) {
    case 400: return "Bad Request";
    case 401: return "Unauthorized";
    case 403: return "Forbidden";
    case 404: return "Not Found";
    case 405: return "Method Not Allowed";
    case 406: return "Not Acceptable";
    case 408: return "Request Timeout";
    case 409: return "Conflict";
    case 411: return "Length Required";
    case 413: return "Payload Too Large";
    case 414: return "URI Too Long";
    case 415: return "Unsupported Media Type";
    case 416: return "Range Not Satisfiable";
    case 421: return "Misdirected Request";
    case 422: return "Unprocessable Content";
    case 431: return "Request Header Fields Too Large";
    case 500: return "Internal Server Error";
    case 501: return "Not Implemented";
    case 503: return "Service Unavailable";
    default: return status >= 500 ? "Server Error" : "Client Error";
  }
}

std::string dumpJson(const Json& doc) {
  return doc.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

Json problemDocument(const ApiError& error, const std::string& instance) {
  Json doc = Json::object();
  doc["type"] = error.type();
  doc["title"] = error.title();
  doc["status"] = error.status();
  doc["detail"] = error.what();
  if (!error.field().empty()) doc["field"] = error.field();
  if (!instance.empty()) doc["instance"] = instance;
  for (const auto& [key, value] : error.extra().items()) doc[key] = value;
  return doc;
}

ApiError problemForStatus(int status, const std::string& detail) {
  const char* type = problem::kInvalidRequest;
  std::string text = detail;
  switch (status) {
    case 404:
      type = problem::kNotFound;
      if (text.empty()) text = "no resource at this path; see GET / for the links";
      break;
    case 405: type = problem::kMethodNotAllowed; break;
    case 411:
      type = problem::kLengthRequired;
      if (text.empty()) text = "chunked request bodies are not accepted; send Content-Length";
      break;
    case 413:
      type = problem::kPayloadTooLarge;
      if (text.empty()) text = "the request body is larger than the server accepts (--max-request-bytes)";
      break;
    case 416: type = problem::kRangeNotSatisfiable; break;
    case 408: type = problem::kRequestTimeout; break;
    case 431: type = problem::kHeadersTooLarge; break;
    case 503: type = problem::kUnavailable; break;
    default:
      if (status >= 500) type = problem::kInternal;
      break;
  }
  if (text.empty()) text = statusTitle(status);
  return ApiError(status, type, statusTitle(status), text);
}

}  // namespace rupture::server
