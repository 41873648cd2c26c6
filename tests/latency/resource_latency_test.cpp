// What issues 25 and 56 bound in time, on a real loopback server: /health while a 1,000-run job is
// created, while eight PNGs render and while 32 thumbnails or series plots are asked for at once,
// how soon SIGTERM ends a server that is drawing pictures, and how soon a 2-million-particle SPH
// run frees its worker after DELETE. Its own executable, run alone (RUN_SERIAL): these tests time the server, and other
// tests' load on the same two cores would time them instead.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <iostream>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "rupture/run.hpp"
#include "server_test_support.hpp"

namespace rupture::server {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using test::expectProblem;
using test::getJson;
using test::kExecutePath;
using test::LiveServer;

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// Polls /health on its own connection until stopped; keeps every answer's latency.
class HealthProbe {
public:
  explicit HealthProbe(int port) : m_port(port), m_thread([this] { loop(); }) {}
  ~HealthProbe() { stop(); }
  void stop() {
    m_stop = true;
    if (m_thread.joinable()) m_thread.join();
  }
  const std::vector<double>& latencies() const { return m_latencies; }
  int failures() const { return m_failures; }
  /// Polls slower than `limit` seconds.
  std::size_t slowerThan(double limit) const {
    return static_cast<std::size_t>(std::count_if(m_latencies.begin(), m_latencies.end(), [&](double s) { return s > limit; }));
  }
  double worst() const { return m_latencies.empty() ? 0 : *std::max_element(m_latencies.begin(), m_latencies.end()); }

private:
  void loop() {
    httplib::Client client("127.0.0.1", m_port);
    client.set_read_timeout(30, 0);
    while (!m_stop) {
      const auto t0 = Clock::now();
      auto res = client.Get("/health");
      if (!res || res->status != 200) ++m_failures;
      else m_latencies.push_back(secondsSince(t0));
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  int m_port;
  std::atomic<bool> m_stop{false};
  std::vector<double> m_latencies;
  int m_failures = 0;
  std::thread m_thread;
};

/// /health stays answered: every poll succeeds, at most one (a scheduling hiccup on a loaded
/// machine) takes over 100 ms, none over a second.
void expectHealthResponsive(const HealthProbe& probe) {
  EXPECT_EQ(probe.failures(), 0);
  EXPECT_GT(probe.latencies().size(), 3u);
  EXPECT_LE(probe.slowerThan(0.1), 1u) << "worst " << probe.worst() << " s of " << probe.latencies().size() << " polls";
  EXPECT_LT(probe.worst(), 1.0);
}

std::uintmax_t treeBytes(const fs::path& dir) {
  std::uintmax_t total = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file()) total += entry.file_size();
  return total;
}

// -- bounded fan-out ---------------------------------------------------------------------------

TEST(ResourceLatency, AThousandRunJobWithAMegabyteDescriptionIsStoredOnceAndHealthStaysAnswered) {
  ASSERT_TRUE(test::scenarioAvailable());
  // Nothing starts (the disk floor is never met), so the data folder holds only the job store.
  LiveServer live([](ServerConfig& c) {
    c.minFreeBytes = std::numeric_limits<long long>::max();
    c.maxRequestBytes = 2 << 20;
  });
  auto client = live.client();
  Json inputs = test::smallInputs();
  const std::string description(1'000'000, 'd');
  inputs["description"] = description;
  Json rates = Json::array();
  for (int k = 0; k < 1000; ++k) rates.push_back(1e5 + 100.0 * k);
  const Json body = {{"inputs", inputs}, {"sweep", {{"loading.strain_rate", rates}}}};
  const std::uintmax_t before = treeBytes(live.dataDir());
  HealthProbe probe(live.port());
  const auto t0 = Clock::now();
  auto res = test::postJson(*client, kExecutePath, body);
  const double seconds = secondsSince(t0);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  probe.stop();
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 201) << res->body.substr(0, 500);
  const std::int64_t id = std::stoll(Json::parse(res->body)["jobID"].get<std::string>());
  const std::uintmax_t grown = treeBytes(live.dataDir()) - before;
  std::cout << "[ fan-out  ] 1000 runs x 1 MB description: created in " << seconds << " s, data folder +" << grown
            << " B, /health worst " << probe.worst() << " s over " << probe.latencies().size() << " polls\n";
  EXPECT_LT(grown, 2 * description.size());
  EXPECT_LT(seconds, 30.0);  // the documented bound (docs/server.md); measured a few seconds
  expectHealthResponsive(probe);
  // Every run still carries the whole spec: the description and its own swept value.
  const Json run = getJson(*client, "/jobs/" + std::to_string(id) + "/runs/999");
  EXPECT_EQ(run["spec"]["description"], description);
  EXPECT_EQ(run["spec"]["loading"]["strain_rate"], rates[999]);
  EXPECT_EQ(run["spec"]["scenario"], test::kScenario);
  // The queue bound: a second such job would pass --max-queued-runs' 1500 (set below).
}

// -- bounded renders ---------------------------------------------------------------------------

/// Submits one quick run of the small example and waits for it: the job's id, or 0 when it did not
/// succeed (the caller asserts).
std::int64_t finishedQuickJob(httplib::Client& client) {
  const auto knob = test::runLengthKnob();
  const Json body = {{"inputs", test::smallInputs()}, {"sweep", {{knob.path, Json::array({knob.quick})}}}};
  const std::int64_t id = test::submit(client, body);
  if (id <= 0) return 0;
  return test::waitForJob(client, id, {"successful", "failed"}, 120)["status"] == "successful" ? id : 0;
}

TEST(ResourceLatency, RendersAreCappedInPixelsAndInConcurrencyAndHealthStaysAnswered) {
  ASSERT_TRUE(test::scenarioAvailable());
  LiveServer live;
  auto client = live.client();
  const std::int64_t id = finishedQuickJob(*client);
  ASSERT_GT(id, 0) << "the quick run did not succeed";
  const std::string plot = "/jobs/" + std::to_string(id) + "/summary.svg?x=" + test::runLengthKnob().path + "&y=peak_stress&format=png";
  // 4000 x 3000 at scale 4: 192 Mpx, refused before any work, naming the parameter.
  expectProblem(client->Get((plot + "&scale=4&width=4000&height=3000").c_str()), 400, "scale");
  expectProblem(client->Get((plot + "&width=4000&height=3000").c_str()), 400, "width");
  // Eight at once within the cap: each answered with a PNG or told to retry; /health unaffected.
  HealthProbe probe(live.port());
  std::vector<int> statuses(8, 0);
  std::vector<std::thread> renders;
  for (int k = 0; k < 8; ++k) {
    renders.emplace_back([&, k] {
      httplib::Client c("127.0.0.1", live.port());
      c.set_read_timeout(60, 0);
      auto res = c.Get((plot + "&scale=2&width=1600&height=1200").c_str());
      if (!res) return;
      statuses[k] = res->status;
      if (res->status == 503) {
        EXPECT_FALSE(res->get_header_value("Retry-After").empty());
      } else if (res->status == 200) {
        EXPECT_EQ(res->body.substr(1, 3), "PNG");
      }
    });
  }
  for (auto& t : renders) t.join();
  probe.stop();
  const auto ok = std::count(statuses.begin(), statuses.end(), 200);
  const auto busy = std::count(statuses.begin(), statuses.end(), 503);
  EXPECT_EQ(ok + busy, 8);
  EXPECT_GE(ok, 2);  // the two rendering slots and their two waiters at least
  expectHealthResponsive(probe);
}

// -- issue 56: thumbnails and series plots behind the gate; SIGTERM while pictures are drawn -------

/// `count` GETs of `path` at once, each on its own connection; the statuses (0: no answer), every
/// 503 checked for its Retry-After and every 200 for a PNG.
std::vector<int> getAtOnce(int port, const std::string& path, int count) {
  std::vector<int> statuses(static_cast<std::size_t>(count), 0);
  std::vector<std::thread> threads;
  for (int k = 0; k < count; ++k)
    threads.emplace_back([&, k] {
      httplib::Client c("127.0.0.1", port);
      c.set_read_timeout(120, 0);
      auto res = c.Get(path.c_str());
      if (!res) return;
      statuses[static_cast<std::size_t>(k)] = res->status;
      if (res->status == 503) {
        EXPECT_FALSE(res->get_header_value("Retry-After").empty());
      } else {
        EXPECT_EQ(res->status, 200) << res->body.substr(0, 300);
        EXPECT_EQ(res->body.substr(1, 3), "PNG");
      }
    });
  for (auto& t : threads) t.join();
  return statuses;
}

TEST(ResourceLatency, ThumbnailsAndSeriesPngsWaitForRenderSlotsAndHealthStaysAnswered) {
  ASSERT_TRUE(test::scenarioAvailable());
  LiveServer live;  // 8 HTTP threads, 2 renders at once and 4 waiting
  auto client = live.client();
  const std::int64_t id = finishedQuickJob(*client);
  ASSERT_GT(id, 0) << "the quick run did not succeed";
  const std::string run = "/jobs/" + std::to_string(id) + "/runs/0";
  // The probe: 32 thumbnails of 4000 x 2000 (the most the pixel cap allows), then 32
  // series PNGs of that size, all at once.
  for (const std::string& path : {run + "/field?thumbnail=1&width=4000&height=2000",
                                  run + "/series?format=png&width=4000&height=2000"}) {
    HealthProbe probe(live.port());
    const auto t0 = Clock::now();
    const std::vector<int> statuses = getAtOnce(live.port(), path, 32);
    const double seconds = secondsSince(t0);
    probe.stop();
    const auto ok = std::count(statuses.begin(), statuses.end(), 200);
    const auto busy = std::count(statuses.begin(), statuses.end(), 503);
    std::cout << "[ renders  ] 32 x " << path.substr(path.rfind('/') + 1) << ": " << ok << " drawn, " << busy
              << " told to retry, in " << seconds << " s; /health worst " << probe.worst() << " s over "
              << probe.latencies().size() << " polls\n";
    EXPECT_EQ(ok + busy, 32);
    EXPECT_GE(ok, 2);
    EXPECT_GT(busy, 0) << "32 renders at once cannot all have had a slot";
    expectHealthResponsive(probe);
  }
}

TEST(ResourceLatency, SigtermWithRendersInFlightExitsWithinTwoSeconds) {
  ASSERT_TRUE(test::scenarioAvailable());
  test::TempDir data;
  test::ChildServer server(data.path());
  auto client = server.client();
  const std::int64_t id = finishedQuickJob(*client);
  ASSERT_GT(id, 0) << "the quick run did not succeed";
  const std::string field = "/jobs/" + std::to_string(id) + "/runs/0/field?bonds=all&width=4000&height=2000";
  // Six large pictures: two drawing, four waiting for a turn, as /health shows them.
  std::vector<std::thread> renders;
  std::atomic<int> answered{0};
  for (int k = 0; k < 6; ++k)
    renders.emplace_back([&, k] {
      httplib::Client c("127.0.0.1", server.port());
      c.set_read_timeout(60, 0);
      auto res = c.Get((field + "&max=" + std::to_string(k + 1)).c_str());  // six distinct pictures
      if (res) {
        EXPECT_TRUE(res->status == 200 || res->status == 503) << res->status;
      }
      ++answered;
    });
  Json health;
  ASSERT_TRUE(test::waitFor([&] {
    auto res = client->Get("/health");
    if (!res || res->status != 200) return false;
    health = Json::parse(res->body);
    return health["renders"]["running"].get<int>() + health["renders"]["waiting"].get<int>() >= 5;
  }, 30)) << health.dump();
  const auto t0 = Clock::now();
  EXPECT_EQ(server.stop(SIGTERM, 20), 0);
  const double seconds = secondsSince(t0);
  std::cout << "[ sigterm  ] with " << health["renders"]["running"] << " renders drawing and "
            << health["renders"]["waiting"] << " waiting: exited after " << seconds << " s\n";
  EXPECT_LT(seconds, 2.0);
  for (auto& t : renders) t.join();
  EXPECT_EQ(answered, 6);
}

// -- prompt cancel of a 2-million-particle SPH run -------------------------------------------------

TEST(ResourceLatency, ATwoMillionParticleSphRunFreesItsWorkerWithinASecondOfDelete) {
  // A 3D piston column at 0.8 mm: 2.0 M water particles and their walls.
  Json inputs = {{"dimension", 3},
                 {"geometry", {{"diameter", 0.08}, {"column_height", 0.203}}},
                 {"resolution", {{"spacing", 0.0008}}},
                 {"fluid", {{"sound_speed", 1450}}},
                 {"piston", {{"motion", "free"}, {"mass", 245}, {"speed", 5}}},
                 {"run", {{"end_time", 0.001}}}};  // with its default snapshots, at 0 and at the end
  Json spec = inputs;
  spec["scenario"] = "piston-column";
  ASSERT_GT(rupture::estimateRun(nlohmann::json(spec)).particles, 2e6);
  LiveServer live([](ServerConfig& c) { c.workers = 1; });
  auto client = live.client();
  for (double after : {0.5, 2.0, 5.0, 8.0}) {
    auto res = test::postJson(*client, "/processes/piston-column/execution", Json{{"inputs", inputs}});
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 201) << res->body;
    const std::string job = "/jobs/" + Json::parse(res->body)["jobID"].get<std::string>();
    ASSERT_TRUE(test::waitFor([&] { return getJson(*client, job)["runs_by_status"]["running"] == 1; }, 30));
    std::this_thread::sleep_for(std::chrono::duration<double>(after));
    const auto t0 = Clock::now();
    auto deleted = client->Delete(job.c_str());
    ASSERT_TRUE(deleted);
    ASSERT_EQ(deleted->status, 200);
    Json doc;
    ASSERT_TRUE(test::waitFor([&] {
      doc = getJson(*client, "/health");
      return doc["running"] == 0;
    }, 30));
    const double freed = secondsSince(t0);
    std::cout << "[ cancel   ] deleted " << after << " s into the run: worker free after " << freed << " s\n";
    EXPECT_LT(freed, 1.0) << "deleted " << after << " s in";
    EXPECT_EQ(getJson(*client, job)["status"], "dismissed");
  }
}

}  // namespace
}  // namespace rupture::server
