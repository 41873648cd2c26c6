// Fuzzing the HTTP boundary with a fixed seed: thousands of mutated job submissions through the
// POST endpoint, and raw requests with random bytes in the request line and headers. Every answer
// must be a 4xx or 201 (never a 5xx, never a dropped connection for a well-framed request), every
// problem document valid UTF-8 JSON, and the server must be alive afterwards.
#include <random>

#include <gtest/gtest.h>

#include "server_test_support.hpp"
#include "common/utf8.hpp"

namespace rupture::server {
namespace {

using test::LiveServer;


/// Snippets that reach parser corners: overflow, control characters, invalid UTF-8, structure.
const std::vector<std::string>& tokens() {
  static const std::vector<std::string> list = {
      "1e400",  "-1e400", "1e-400", "NaN",    "Infinity", "-0",      "0x10",    "1.",     "null", "true",
      "\"\"",   "{}",     "[]",     "{",      "[",        "}",       "]",       ",",      ":",    "\"",
      "\\",     "\\u0000", "\\ud800", "\xFF", "\xC3\x28", "\xED\xA0\x80", "\xEF\xBF\xBE", "\x01", std::string(1, '\0'),
      "\"\":1", "9223372036854775808", "-9223372036854775809", "1e308", "\"scenario\":\"x\"", "\"sweep\":{}",
  };
  return list;
}

/// One mutation of `text`: a byte flipped, inserted or deleted, a span duplicated or dropped, or a
/// token spliced in.
std::string mutateText(std::string text, std::mt19937_64& rng) {
  auto pick = [&](std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(rng() % n); };
  const int rounds = 1 + static_cast<int>(rng() % 3);
  for (int r = 0; r < rounds; ++r) {
    const std::size_t at = pick(text.size() + 1);
    switch (rng() % 6) {
      case 0:
        if (!text.empty()) text[pick(text.size())] = static_cast<char>(rng() & 0xFF);
        break;
      case 1: text.insert(at, 1, static_cast<char>(rng() & 0xFF)); break;
      case 2: text.erase(at, 1 + pick(8)); break;
      case 3: {
        const std::size_t len = pick(32);
        text.insert(at, text.substr(pick(text.size() + 1), len));
        break;
      }
      case 4: text.erase(at, pick(64)); break;
      default: text.insert(at, tokens()[pick(tokens().size())]); break;
    }
  }
  return text;
}

/// A random JSON value, for structural mutations that keep the text valid JSON.
Json randomValue(std::mt19937_64& rng, int depth = 0) {
  switch (rng() % (depth > 2 ? 6 : 8)) {
    case 0: return nullptr;
    case 1: return static_cast<bool>(rng() & 1);
    case 2: return static_cast<std::int64_t>(rng()) >> (rng() % 64);
    case 3: return std::ldexp(static_cast<double>(rng() % 2001) - 1000.0, static_cast<int>(rng() % 200) - 100);
    case 4: return tokens()[rng() % tokens().size()] + "x";
    case 5: return "";
    case 6: {
      Json a = Json::array();
      for (std::size_t i = 0, n = rng() % 4; i < n; ++i) a.push_back(randomValue(rng, depth + 1));
      return a;
    }
    default: {
      Json o = Json::object();
      for (std::size_t i = 0, n = rng() % 3; i < n; ++i) o[rng() % 4 ? "k" + std::to_string(i) : ""] = randomValue(rng, depth + 1);
      return o;
    }
  }
}

/// Replaces one value somewhere in `doc` (objects and arrays walked at random) with a random value.
void mutateStructure(Json& doc, std::mt19937_64& rng) {
  Json* node = &doc;
  for (int depth = 0; depth < 6 && (node->is_object() || node->is_array()) && !node->empty(); ++depth) {
    auto it = node->begin();
    std::advance(it, static_cast<std::ptrdiff_t>(rng() % node->size()));
    if (rng() % 3 == 0) {
      *it = randomValue(rng);
      return;
    }
    node = &*it;
  }
  *node = randomValue(rng);
}

TEST(HttpFuzz, MutatedSubmissionsNeverGetA5xx) {
  ASSERT_TRUE(test::scenarioAvailable());
  // Runs would compete with the fuzzing for the CPU; the limit keeps accepted sweeps small.
  LiveServer live([](ServerConfig& c) {
    c.workers = 1;
    c.maxRuns = 4;
  });
  auto client = live.client();
  const auto knob = test::runLengthKnob();
  Json base = {{"inputs", test::smallInputs()},
               {"sweep", {{knob.path, Json::array({knob.quick})}}},
               {"sweep_mode", "grid"},
               {"name", "fuzz"}};
  const std::string baseText = base.dump();

  std::mt19937_64 rng(20261123);
  constexpr int kCases = 3000;
  int accepted = 0, rejected = 0, serverErrors = 0, noAnswer = 0, badDocuments = 0;
  for (int i = 0; i < kCases; ++i) {
    std::string body;
    if (i % 2 == 0) {
      body = mutateText(baseText, rng);
    } else {
      Json doc = base;
      for (int k = 0, n = 1 + static_cast<int>(rng() % 3); k < n; ++k) mutateStructure(doc, rng);
      body = doc.dump(-1, ' ', false, Json::error_handler_t::replace);
    }
    auto res = client->Post(test::kExecutePath.c_str(), body, "application/json");
    if (!res) {
      ++noAnswer;
      ADD_FAILURE() << "case " << i << ": no answer (" << httplib::to_string(res.error()) << ") for "
                    << body.substr(0, 200);
      client = live.client();
      continue;
    }
    if (res->status >= 500) {
      ++serverErrors;
      ADD_FAILURE() << "case " << i << ": " << res->status << " " << res->body << " for " << body.substr(0, 300);
    } else if (res->status == 201) {
      ++accepted;
    } else {
      ++rejected;
      EXPECT_GE(res->status, 400) << body.substr(0, 300);
      const bool valid = isValidUtf8(res->body) && Json::accept(res->body);
      if (!valid) {
        ++badDocuments;
        ADD_FAILURE() << "case " << i << ": the problem document is not UTF-8 JSON: " << res->body;
      }
    }
  }
  std::cout << "[ fuzz     ] " << kCases << " submissions: " << accepted << " accepted, " << rejected << " rejected (4xx), "
            << serverErrors << " 5xx, " << noAnswer << " without answer, " << badDocuments << " bad documents\n";
  EXPECT_EQ(accepted + rejected, kCases);
  EXPECT_GT(rejected, kCases / 2);  // most mutations are invalid...
  EXPECT_GT(accepted, 0);           // ...and some are not: the valid path was exercised too
  auto health = client->Get("/health");
  ASSERT_TRUE(health);
  EXPECT_EQ(health->status, 200);
}

TEST(HttpFuzz, RandomBytesInRequestLinesAndHeadersNeverGetA5xx) {
  LiveServer live([](ServerConfig& c) { c.requestTimeout = 0.5; });
  std::mt19937_64 rng(77);
  const std::vector<std::string> targets = {"/", "/jobs", "/jobs/1", "/processes/dynamic-tension/execution",
                                            "/jobs/1/runs/0/results", "/jobs?status=running"};
  auto randomBytes = [&](std::size_t n) {
    std::string s;
    for (std::size_t i = 0; i < n; ++i) s += static_cast<char>(rng() & 0xFF);
    return s;
  };
  constexpr int kCases = 600;
  int answered = 0, serverErrors = 0;
  for (int i = 0; i < kCases; ++i) {
    std::string target = targets[rng() % targets.size()];
    std::string headerName = "X-Fuzz", headerValue = "v";
    switch (rng() % 5) {
      case 0: target.insert(rng() % (target.size() + 1), randomBytes(1 + rng() % 6)); break;
      case 1: target += "%" + randomBytes(2); break;
      case 2: headerValue = randomBytes(1 + rng() % 40); break;
      case 3: headerName = randomBytes(1 + rng() % 10); break;
      default: target = "/" + randomBytes(1 + rng() % 20); break;
    }
    // Line breaks inside the random parts would end the head early: keep them out of the fields.
    for (std::string* s : {&target, &headerName, &headerValue}) {
      for (char& c : *s) {
        if (c == '\r' || c == '\n') c = 'x';
      }
    }
    const std::string method = (rng() & 1) ? "GET" : "DELETE";
    const std::string request = method + " " + target + " HTTP/1.1\r\nHost: 127.0.0.1\r\n" + headerName + ": " +
                                headerValue + "\r\nConnection: close\r\n\r\n";
    const std::string response = test::rawExchange(live.port(), request, 3);
    const int status = test::rawStatus(response);
    if (status > 0) ++answered;
    if (status >= 500) {
      ++serverErrors;
      ADD_FAILURE() << "a " << status << " for " << request.substr(0, 200);
    }
    if (status > 0 && response.find("application/problem+json") != std::string::npos) {
      EXPECT_TRUE(isValidUtf8(test::rawBody(response))) << response;
    }
  }
  std::cout << "[ fuzz     ] " << kCases << " raw requests: " << answered << " answered, " << serverErrors << " 5xx\n";
  EXPECT_EQ(serverErrors, 0);
  EXPECT_GT(answered, kCases * 9 / 10);
  auto client = live.client();
  auto health = client->Get("/health");
  ASSERT_TRUE(health);
  EXPECT_EQ(health->status, 200);
}

}  // namespace
}  // namespace rupture::server
