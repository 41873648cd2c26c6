// A run's pictures and page over HTTP: GET /jobs/{id}/runs/{k}/field (PNG of the asked size with
// the field's colours, SVG, PDF, thumbnails, a 304 for a picture the client holds), the series as
// a plot, the run page with its picture, strip, series and summary, the job page's thumbnails, and
// every bad parameter refused with a 400 naming it; every picture waits for a render slot (503 with
// Retry-After beyond the waiters) and is held to the pixel cap (issue 56).
#include <atomic>
#include <future>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "server_test_support.hpp"
#include "support/html_check.hpp"
#include "support/png_probe.hpp"
#include "views/render_gate.hpp"

namespace rupture::server {
namespace {

using rupture::testing::probePng;

class RunPictures : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    live = std::make_unique<test::LiveServer>();
    auto client = live->client();
    jobId = test::submit(*client, Json{{"inputs", test::smallInputs()}, {"name", "pictures"},
                                       {"sweep", {{"loading.strain_rate", test::twoStrainRates()}}}});
    ASSERT_EQ(test::waitForJob(*client, jobId, {"successful", "failed"}, 180)["status"], "successful");
  }
  static void TearDownTestSuite() { live.reset(); }
  static std::string run(int k) { return "/jobs/" + std::to_string(jobId) + "/runs/" + std::to_string(k); }
  static void expectRefused(httplib::Client& client, const std::string& path, const std::string& field) {
    auto res = client.Get(path.c_str());
    ASSERT_TRUE(res) << path;
    EXPECT_EQ(res->status, 400) << path << ": " << res->body;
    EXPECT_EQ(Json::parse(res->body).value("field", ""), field) << path << ": " << res->body;
  }
  static inline std::unique_ptr<test::LiveServer> live;
  static inline std::int64_t jobId = 0;
};

TEST_F(RunPictures, TheFieldAsPngSvgPdfAndThumbnail) {
  auto client = live->client();
  auto png = client->Get((run(0) + "/field").c_str());
  ASSERT_TRUE(png);
  ASSERT_EQ(png->status, 200) << png->body;
  EXPECT_EQ(png->get_header_value("Content-Type"), "image/png");
  EXPECT_EQ(png->get_header_value("X-Field"), "damage");
  const auto picture = probePng(png->body);
  EXPECT_EQ(picture.width, 800);
  EXPECT_EQ(picture.height, 600);
  EXPECT_GT(picture.colours, 50u) << "a field, not one colour";
  EXPECT_GT(picture.near(68, 1, 84), 10000u) << "undamaged elements in viridis' first colour";

  // The same picture again costs a 304 when the client holds it.
  const std::string tag = png->get_header_value("ETag");
  ASSERT_FALSE(tag.empty());
  auto again = client->Get((run(0) + "/field").c_str(), httplib::Headers{{"If-None-Match", tag}});
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 304);
  auto other = client->Get((run(0) + "/field?snapshot=0").c_str(), httplib::Headers{{"If-None-Match", tag}});
  ASSERT_TRUE(other);
  EXPECT_EQ(other->status, 200) << "another query is another picture";

  auto svg = client->Get((run(1) + "/field?field=von_mises&format=svg").c_str());
  ASSERT_TRUE(svg);
  EXPECT_EQ(svg->status, 200);
  EXPECT_EQ(svg->get_header_value("Content-Type"), "image/svg+xml");
  EXPECT_NE(svg->body.find("<svg"), std::string::npos);
  // Measurable: axes with their unit, colour ticks at round values, the loading marked (the
  // picture's words in its <desc>; cairo draws the text itself as outlines).
  const std::size_t desc = svg->body.find("<desc id=\"picture-description\">");
  ASSERT_NE(desc, std::string::npos) << svg->body.substr(0, 600);
  const std::string words = svg->body.substr(desc, svg->body.find("</desc>", desc) - desc);
  EXPECT_NE(words.find("x axis (µm)"), std::string::npos) << words;
  EXPECT_NE(words.find("y axis (µm)"), std::string::npos) << words;
  EXPECT_NE(words.find("colour bar: Von Mises stress (MPa)"), std::string::npos) << words;
  EXPECT_NE(words.find("loading: pulled at 1e7 /s, along +x at the largest x face"), std::string::npos) << words;
  EXPECT_NE(words.find("loading: held at the smallest x face"), std::string::npos) << words;
  std::string error;
  EXPECT_TRUE(test::wellFormedXml(svg->body, error)) << "the words added keep the SVG well-formed: " << error;
  auto pdf = client->Get((run(1) + "/field?format=pdf").c_str());
  ASSERT_TRUE(pdf);
  EXPECT_EQ(pdf->get_header_value("Content-Type"), "application/pdf");
  EXPECT_EQ(pdf->body.rfind("%PDF", 0), 0u);
  auto thumbnail = client->Get((run(1) + "/field?thumbnail=1").c_str());
  ASSERT_TRUE(thumbnail);
  const auto small = probePng(thumbnail->body);
  EXPECT_EQ(small.width, 200);
  EXPECT_EQ(small.height, 150);
}

/// The colour range a picture was drawn with, from its X-Colour-Range header.
std::pair<double, double> colourRange(const httplib::Result& res) {
  const Json range = Json::parse(res->get_header_value("X-Colour-Range"));
  return {range.at(0).get<double>(), range.at(1).get<double>()};
}

TEST_F(RunPictures, TheColourRangeIsTheRunsByDefaultAndFollowsMinAndMax) {
  auto client = live->client();
  auto first = client->Get((run(1) + "/field?field=von_mises&snapshot=0&thumbnail=1").c_str());
  auto last = client->Get((run(1) + "/field?field=von_mises&snapshot=-1&thumbnail=1").c_str());
  ASSERT_TRUE(first && last);
  ASSERT_EQ(first->status, 200) << first->body;
  ASSERT_EQ(last->status, 200) << last->body;
  // One colour is one stress on every snapshot of the run: the same range on both.
  EXPECT_EQ(first->get_header_value("X-Colour-Range-Source"), "run");
  EXPECT_EQ(colourRange(first), colourRange(last));
  EXPECT_GT(colourRange(last).second, 1e6) << "the run's stresses reach MPa";
  // Each snapshot its own range when asked: the first snapshot (at rest) spans less.
  auto own = client->Get((run(1) + "/field?field=von_mises&snapshot=0&thumbnail=1&range=snapshot").c_str());
  ASSERT_TRUE(own);
  ASSERT_EQ(own->status, 200) << own->body;
  EXPECT_EQ(own->get_header_value("X-Colour-Range-Source"), "snapshot");
  EXPECT_LT(colourRange(own).second, colourRange(first).second);
  // A range given is the range drawn.
  auto asked = client->Get((run(1) + "/field?field=von_mises&min=1e6&max=5e7&thumbnail=1").c_str());
  ASSERT_TRUE(asked);
  ASSERT_EQ(asked->status, 200) << asked->body;
  EXPECT_EQ(asked->get_header_value("X-Colour-Range-Source"), "asked");
  EXPECT_EQ(colourRange(asked), (std::pair<double, double>{1e6, 5e7}));
  expectRefused(*client, run(1) + "/field?range=job", "range");

  // The run page offers the range: its form, and the pictures it shows follow it.
  auto page = client->Get((run(1) + "?f=html&field=von_mises&min=1000000&max=50000000").c_str());
  ASSERT_TRUE(page);
  ASSERT_EQ(page->status, 200) << page->body.substr(0, 300);
  const std::string& html = page->body;
  EXPECT_NE(html.find("name=\"min\""), std::string::npos);
  EXPECT_NE(html.find("name=\"max\""), std::string::npos);
  EXPECT_NE(html.find("value=\"1000000.0\""), std::string::npos) << "the asked minimum kept in the form";
  EXPECT_NE(html.find("&amp;min=1000000.0&amp;max=50000000.0"), std::string::npos) << "the picture follows the form";
  EXPECT_NE(html.find("the range asked for"), std::string::npos);
  EXPECT_NE(html.find("Snapshots are numbered from 0"), std::string::npos);
  expectRefused(*client, run(1) + "?f=html&min=5&max=1", "max");
  auto plain = client->Get((run(1) + "?f=html").c_str());
  ASSERT_TRUE(plain);
  EXPECT_NE(plain->body.find("the field's range over every snapshot"), std::string::npos)
      << "the default said in words";
}

// Issue 55: every form and picture page passes an HTML check (closed in order, quoted, unique ids).
TEST_F(RunPictures, EveryPicturePageAndFormPassesTheHtmlCheck) {
  auto client = live->client();
  const std::string job = "/jobs/" + std::to_string(jobId);
  std::vector<std::string> pages = {run(0) + "?f=html", run(1) + "?f=html&field=von_mises&min=1e6&max=5e7&range=snapshot",
                                    job + "?f=html", "/jobs?f=html", "/summary?f=html&jobs=" + std::to_string(jobId),
                                    "/?f=html", "/processes?f=html"};
  const Json processes = test::getJson(*client, "/processes");
  for (const auto& p : processes.value("processes", Json::array()))
    pages.push_back("/processes/" + p.value("id", "") + "?f=html");
  ASSERT_GT(pages.size(), 9u) << "every scenario's form";
  for (const std::string& path : pages) {
    auto res = client->Get(path.c_str());
    ASSERT_TRUE(res) << path;
    ASSERT_EQ(res->status, 200) << path << ": " << res->body.substr(0, 300);
    EXPECT_EQ(rupture::testing::htmlProblems(res->body), "") << path;
  }
  // The check finds what it is for.
  EXPECT_NE(rupture::testing::htmlProblems("<!DOCTYPE html>\n<html><body><p>a</div></body></html>"), "");
  EXPECT_NE(rupture::testing::htmlProblems("<!DOCTYPE html>\n<html><body><p id=a></p></body></html>"), "");
  EXPECT_NE(rupture::testing::htmlProblems("<!DOCTYPE html>\n<html><body><p id=\"a\"></p><b id=\"a\"></b></body></html>"), "");
  EXPECT_NE(rupture::testing::htmlProblems("<!DOCTYPE html>\n<html><body>R & D</body></html>"), "");
  EXPECT_EQ(rupture::testing::htmlProblems("<!DOCTYPE html>\n<html><body><img src=\"a\"><br>R &amp; D</body></html>"), "");
}

TEST_F(RunPictures, TheSeriesAsAPlot) {
  auto client = live->client();
  auto plot = client->Get((run(0) + "/series?format=png&y=stress_mean&width=600&height=400").c_str());
  ASSERT_TRUE(plot);
  ASSERT_EQ(plot->status, 200) << plot->body;
  const auto png = probePng(plot->body);
  EXPECT_EQ(png.width, 600);
  EXPECT_EQ(png.height, 400);
  auto svg = client->Get((run(0) + "/series?format=svg").c_str());
  ASSERT_TRUE(svg);
  EXPECT_EQ(svg->get_header_value("Content-Type"), "image/svg+xml");
  // The data formats are unchanged.
  auto csv = client->Get((run(0) + "/series?format=csv").c_str());
  ASSERT_TRUE(csv);
  EXPECT_EQ(csv->get_header_value("Content-Type").rfind("text/csv", 0), 0u);
  EXPECT_NE(csv->body.substr(0, csv->body.find('\n')).find("time [s]"), std::string::npos) << csv->body.substr(0, 100);
}

TEST_F(RunPictures, BadParametersAreRefusedNamingThem) {
  auto client = live->client();
  expectRefused(*client, run(0) + "/field?fontsize=12", "fontsize");
  expectRefused(*client, run(0) + "/field?field=pressure", "field");  // not recorded by a bonded run
  expectRefused(*client, run(0) + "/field?snapshot=abc", "snapshot");
  expectRefused(*client, run(0) + "/field?snapshot=99", "snapshot");
  expectRefused(*client, run(0) + "/field?view=zz", "view");
  expectRefused(*client, run(0) + "/field?bonds=some", "bonds");
  expectRefused(*client, run(0) + "/field?width=10", "width");
  expectRefused(*client, run(0) + "/field?min=2&max=1", "max");
  expectRefused(*client, run(0) + "/field?format=gif", "format");
  expectRefused(*client, run(0) + "/series?format=png&y=no_such_series", "y");
  expectRefused(*client, run(0) + "/series?format=webp", "format");
  expectRefused(*client, run(0) + "?f=html&field=pressure", "field");
  expectRefused(*client, run(0) + "?f=html&snapshot=99", "snapshot");
}

TEST_F(RunPictures, TheRunPageAndTheJobPagesThumbnails) {
  auto client = live->client();
  auto page = client->Get((run(1) + "?f=html").c_str());
  ASSERT_TRUE(page);
  ASSERT_EQ(page->status, 200);
  EXPECT_NE(page->get_header_value("Content-Type").find("text/html"), std::string::npos);
  const std::string& html = page->body;
  EXPECT_NE(html.find("<img id=\"field\""), std::string::npos) << html.substr(0, 2000);
  EXPECT_NE(html.find(run(1) + "/field?field=damage"), std::string::npos);
  EXPECT_NE(html.find("id=\"strip\""), std::string::npos);
  EXPECT_NE(html.find(run(1) + "/series?format=svg"), std::string::npos);
  EXPECT_NE(html.find("Peak stress"), std::string::npos);
  EXPECT_NE(html.find(" MPa</td>"), std::string::npos) << "engineering units in the summary";
  EXPECT_NE(html.find("1e7 /s"), std::string::npos) << "the swept strain rate as people read it";
  EXPECT_NE(html.find("id=\"spec\""), std::string::npos);
  // What made the file: its /provenance, the spec's digest among it.
  const std::size_t made = html.find("id=\"provenance\"");
  ASSERT_NE(made, std::string::npos);
  EXPECT_NE(html.find("spec SHA-256 <code>", made), std::string::npos);
  EXPECT_NE(html.find("seeds <code>{&quot;sample.seed&quot;:", made), std::string::npos) << html.substr(made, 600);
  // Every picture the page names answers 200.
  for (const char* kind : {"/field?", "/series?"}) {
    std::string needle = "src=\"";  // appended piecewise: GCC 12 misreads "..." + std::string&& (-Wrestrict)
    needle.append(run(1)).append(kind);
    const std::size_t at = html.find(needle);
    ASSERT_NE(at, std::string::npos) << needle;
    std::string src;  // the attribute unescaped, copied rather than replaced in place (GCC 12's -Wrestrict)
    for (std::size_t i = at + 5; i < html.size() && html[i] != '"';) {
      const bool amp = html.compare(i, 5, "&amp;") == 0;
      src += html[i];
      i += amp ? 5 : 1;
    }
    auto image = client->Get(src.c_str());
    ASSERT_TRUE(image) << src;
    EXPECT_EQ(image->status, 200) << src << ": " << image->body.substr(0, 300);
  }
  // The job page shows a thumbnail of every run, linking to its page.
  auto jobPage = client->Get(("/jobs/" + std::to_string(jobId) + "?f=html").c_str());
  ASSERT_TRUE(jobPage);
  for (int k : {0, 1}) {
    EXPECT_NE(jobPage->body.find(run(k) + "/field?thumbnail=1"), std::string::npos) << k;
    EXPECT_NE(jobPage->body.find("href=\"" + run(k) + "?f=html\""), std::string::npos) << k;
  }
  // Swept paths are headed by their labels (the path on hover), before and after the summary.
  EXPECT_NE(jobPage->body.find("<th title=\"loading.strain_rate\">Strain rate</th>"), std::string::npos);
  // A comparison's table leads with the job.
  auto compare = client->Get(("/summary?jobs=" + std::to_string(jobId) + "&f=html").c_str());
  ASSERT_TRUE(compare);
  EXPECT_EQ(compare->status, 200);
  EXPECT_NE(compare->body.find("<table id=\"compare\"><tr><th title=\"job\">Job</th><th>Run</th>"), std::string::npos)
      << compare->body.substr(0, 3000);
}

// -- issue 56: every picture behind the render gate and its pixel cap --------------------------------

TEST_F(RunPictures, EveryPictureWaitsForARenderSlotAndBeyondTheWaitersIs503WithRetryAfter) {
  RenderGate& gate = live->server().renderGate();
  // 8 HTTP threads, 2 renders at once: 8 - 2 - 2 = 4 may wait, so two threads stay for the rest.
  ASSERT_EQ(gate.maxRunning(), 2);
  ASSERT_EQ(gate.maxWaiting(), 4);
  // The test holds both slots itself, so that the gate is full however fast the machine draws.
  std::promise<void> letGo;
  const std::shared_future<void> released = letGo.get_future().share();
  std::atomic<int> held{0};
  std::vector<std::thread> holders;
  for (int i = 0; i < gate.maxRunning(); ++i)
    holders.emplace_back([&] {
      const RenderGate::Slot slot = gate.acquire();
      ++held;
      released.wait();
    });
  ASSERT_TRUE(test::waitFor([&] { return held == gate.maxRunning(); }, 5));
  // Four thumbnails wait for a turn (a job page's, as a browser asks for them).
  std::vector<int> waited(4, 0);
  std::vector<std::thread> waiters;
  for (int i = 0; i < 4; ++i)
    waiters.emplace_back([&, i] {
      auto c = live->client();
      auto res = c->Get((run(i % 2) + "/field?thumbnail=1&width=" + std::to_string(160 + i)).c_str());
      if (res) waited[static_cast<std::size_t>(i)] = res->status;
    });
  ASSERT_TRUE(test::waitFor([&] { return gate.waiting() == 4; }, 10)) << gate.waiting();
  // Every other picture is turned away at once, thumbnails and series plots included, with a
  // Retry-After; what draws nothing (/health, the CSV series) is answered as ever.
  auto client = live->client();
  const std::string summaryPng =
      "/jobs/" + std::to_string(jobId) + "/summary.svg?x=loading.strain_rate&y=peak_stress&format=png";
  for (const std::string& path : {run(0) + "/field?thumbnail=1", run(1) + "/field", run(0) + "/series?format=png",
                                  run(0) + "/series?format=svg", run(0) + "/series?format=pdf", summaryPng}) {
    auto res = client->Get(path.c_str());
    test::expectProblem(res, 503);
    ASSERT_TRUE(res) << path;
    EXPECT_EQ(res->get_header_value("Retry-After"), "2") << path;
    EXPECT_NE(res->body.find("--max-renders"), std::string::npos) << res->body;
  }
  const Json health = test::getJson(*client, "/health");
  EXPECT_EQ(health["renders"]["running"], 2) << health.dump();
  EXPECT_EQ(health["renders"]["waiting"], 4) << health.dump();
  auto csv = client->Get((run(0) + "/series?format=csv").c_str());
  ASSERT_TRUE(csv);
  EXPECT_EQ(csv->status, 200);
  // Once the slots are free, the waiting thumbnails are drawn.
  letGo.set_value();
  for (auto& t : holders) t.join();
  for (auto& t : waiters) t.join();
  for (int status : waited) EXPECT_EQ(status, 200);
  EXPECT_EQ(gate.running(), 0);
  EXPECT_EQ(gate.waiting(), 0);
}

TEST_F(RunPictures, ThumbnailsAndSeriesPlotsAreHeldToThePixelCap) {
  auto client = live->client();
  // The suite's server has the default cap, 8,000,000 px: 4000 x 2001 is over it, 4000 x 2000 not.
  for (const std::string& path : {run(0) + "/field?thumbnail=1&width=4000&height=2001",
                                  run(0) + "/series?format=png&width=4000&height=2001"}) {
    auto res = client->Get(path.c_str());
    const Json problem = test::expectProblem(res, 400, "height");
    EXPECT_NE(problem.value("detail", "").find("--max-render-pixels"), std::string::npos) << problem.dump();
    EXPECT_EQ(problem["pixels"], 8'004'000) << path;
  }
  // Vector formats have no pixels.
  auto svg = client->Get((run(0) + "/series?format=svg&width=4000&height=2001").c_str());
  ASSERT_TRUE(svg);
  EXPECT_EQ(svg->status, 200);
}

}  // namespace
}  // namespace rupture::server
