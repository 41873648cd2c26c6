// A job as an RO-Crate (GET /jobs/{id}/crate; docs/provenance.md): the ZIP is read by Python's
// zipfile, an independent reader (names, bytes and CRCs); the metadata holds RO-Crate 1.1's required
// entities and the Workflow Run Crate's, lists every file in the ZIP with its stated size, and its
// request.json, POSTed again, is accepted; the run files carry their provenance; a crate is
// refused while runs are unfinished, and a ZIP member of 4 GiB is refused rather than written wrong.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "io/sha256.hpp"
#include "io/hdf5_file.hpp"
#include "server_test_support.hpp"
#include "views/zip_archive.hpp"

namespace rupture::server {
namespace {

using test::getJson;
using test::LiveServer;
namespace fs = std::filesystem;

std::string readAll(const ZipArchive& zip) {
  std::string bytes(zip.size(), '\0');
  EXPECT_EQ(zip.read(0, bytes.data(), bytes.size()), bytes.size());
  return bytes;
}

void writeBytes(const fs::path& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

/// Extracts `zip` into `into` with Python's zipfile after checking every member's CRC; false when
/// Python could not.
bool extractWithPython(const fs::path& zip, const fs::path& into) {
  const std::string cmd = "/usr/bin/python3 -c \"import sys, zipfile; z = zipfile.ZipFile(sys.argv[1]); "
                          "assert z.testzip() is None; z.extractall(sys.argv[2])\" " +
                          zip.string() + " " + into.string();
  return std::system(cmd.c_str()) == 0;
}

TEST(ZipArchive, Crc32IsTheStandardOne) {
  EXPECT_EQ(ZipArchive::crc32("123456789"), 0xcbf43926u);  // the CRC-32 check value
  EXPECT_EQ(ZipArchive::crc32(""), 0u);
  EXPECT_EQ(ZipArchive::crc32("6789", ZipArchive::crc32("12345")), 0xcbf43926u) << "continues across pieces";
}

TEST(ZipArchive, AnIndependentReaderGetsTheMembersBack) {
  test::TempDir dir;
  std::string large(3 * 1024 * 1024 + 17, '\0');
  for (std::size_t k = 0; k < large.size(); ++k) large[k] = static_cast<char>((k * 2654435761u) >> 13);
  writeBytes(dir.path() / "large.bin", large);
  ZipArchive zip;
  zip.addText("a/readme.txt", "héllo, crate\n", 1700000000);
  zip.addFile("b/large.bin", dir.path() / "large.bin", 1700000000);
  zip.addText("empty", "", 0);
  zip.finish();
  const std::string bytes = readAll(zip);
  // Pieces read at odd offsets give the same bytes as one read.
  std::string pieced;
  for (std::uint64_t at = 0; at < zip.size();) {
    char buffer[7919];
    const std::size_t n = zip.read(at, buffer, sizeof buffer);
    ASSERT_GT(n, 0u);
    pieced.append(buffer, n);
    at += n;
  }
  EXPECT_EQ(pieced, bytes);
  writeBytes(dir.path() / "x.zip", bytes);
  ASSERT_TRUE(extractWithPython(dir.path() / "x.zip", dir.path() / "out"));
  EXPECT_EQ(test::readText(dir.path() / "out" / "a" / "readme.txt"), "héllo, crate\n");
  EXPECT_EQ(test::readText(dir.path() / "out" / "b" / "large.bin"), large);
  EXPECT_TRUE(fs::exists(dir.path() / "out" / "empty"));
  EXPECT_EQ(fs::file_size(dir.path() / "out" / "empty"), 0u);
}

TEST(ZipArchive, AMemberOfFourGibibytesIsRefusedNotWrittenWrong) {
  test::TempDir dir;
  const fs::path huge = dir.path() / "huge.h5";
  std::ofstream(huge).close();
  fs::resize_file(huge, std::uint64_t{1} << 32);  // sparse: no 4 GiB written
  ZipArchive zip;
  EXPECT_THROW(zip.addFile("huge.h5", huge, 0), std::length_error);
}

class JobCrate : public ::testing::Test {
protected:
  void SetUp() override {
    if (!test::scenarioAvailable()) GTEST_SKIP() << "dynamic-tension not registered";
  }
};

TEST_F(JobCrate, DescribesTheJobAndEveryFileItHolds) {
  LiveServer live([](ServerConfig& c) { c.workers = 1; });
  auto client = live.client();
  const Json request = {{"inputs", test::smallInputs()}, {"name", "crate"}};
  const std::int64_t id = test::submit(*client, request);
  ASSERT_GT(id, 0);
  const Json done = test::waitForJob(*client, id, {"successful", "failed"}, 120);
  ASSERT_EQ(done["status"], "successful") << done.dump(2);

  auto res = client->Get(("/jobs/" + std::to_string(id) + "/crate").c_str());
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body.substr(0, 300);
  EXPECT_EQ(res->get_header_value("Content-Type"), "application/zip");
  EXPECT_EQ(res->get_header_value("Content-Length"), std::to_string(res->body.size()));
  test::TempDir dir;
  writeBytes(dir.path() / "crate.zip", res->body);
  const fs::path out = dir.path() / "crate";
  ASSERT_TRUE(extractWithPython(dir.path() / "crate.zip", out)) << "Python's zipfile could not read the crate";

  const Json metadata = Json::parse(test::readText(out / "ro-crate-metadata.json"));
  EXPECT_EQ(metadata["@context"], "https://w3id.org/ro/crate/1.1/context");
  std::map<std::string, Json> graph;
  for (const Json& e : metadata["@graph"]) graph[e["@id"].get<std::string>()] = e;
  ASSERT_TRUE(graph.count("ro-crate-metadata.json") && graph.count("./"));
  EXPECT_EQ(graph["ro-crate-metadata.json"]["about"]["@id"], "./");
  const Json root = graph["./"];
  EXPECT_EQ(root["@type"], "Dataset");
  for (const char* key : {"name", "description", "datePublished", "license", "hasPart", "mainEntity", "mentions"})
    EXPECT_TRUE(root.contains(key)) << key;
  std::set<std::string> profiles;
  for (const Json& p : root["conformsTo"]) profiles.insert(p["@id"]);
  EXPECT_TRUE(profiles.count("https://w3id.org/ro/wfrun/workflow/0.5"));
  EXPECT_TRUE(profiles.count("https://w3id.org/ro/wfrun/process/0.5"));

  // Every listed file is there with its stated size, and the ZIP holds nothing unlisted.
  std::set<std::string> listed = {"ro-crate-metadata.json"};
  for (const Json& part : root["hasPart"]) {
    const std::string name = part["@id"];
    listed.insert(name);
    ASSERT_TRUE(fs::exists(out / name)) << name;
    EXPECT_EQ(graph[name]["contentSize"], std::to_string(fs::file_size(out / name))) << name;
  }
  std::set<std::string> inZip;
  for (const auto& entry : fs::recursive_directory_iterator(out))
    if (entry.is_regular_file()) inZip.insert(fs::relative(entry.path(), out).string());
  EXPECT_EQ(inZip, listed);

  // The workflow is the request, and POSTed again it makes a job.
  const std::string workflow = root["mainEntity"]["@id"];
  EXPECT_EQ(workflow, "request.json");
  const Json accepted = Json::parse(test::readText(out / workflow));
  EXPECT_EQ(accepted["inputs"], request["inputs"]);
  EXPECT_EQ(accepted["name"], "crate");
  EXPECT_GT(test::submit(*client, accepted), id);

  // The job's action runs the workflow; the run's action runs Rupture on its spec into its file.
  const Json jobAction = graph["#job-" + std::to_string(id)];
  EXPECT_EQ(jobAction["@type"], "CreateAction");
  EXPECT_EQ(jobAction["instrument"]["@id"], workflow);
  EXPECT_EQ(jobAction["actionStatus"]["@id"], "http://schema.org/CompletedActionStatus");
  const Json run = graph["#run-0"];
  EXPECT_EQ(run["instrument"]["@id"], "#rupture");
  EXPECT_EQ(graph["#rupture"]["softwareVersion"], RUPTURE_VERSION);
  EXPECT_NE(graph["#rupture"]["description"].get<std::string>().find(done["provenance"]["git_commit"].get<std::string>()),
            std::string::npos);
  EXPECT_EQ(run["object"][0]["@id"], "runs/run-0.json");
  ASSERT_EQ(run["result"][0]["@id"], "runs/run-0.h5");
  EXPECT_EQ(Json::parse(test::readText(out / "runs" / "run-0.json"))["scenario"], test::kScenario);
  const io::Hdf5File h5 = io::Hdf5File::openReadOnly((out / "runs" / "run-0.h5").string());
  EXPECT_EQ(h5.readAttributeString("/provenance", "spec_sha256"), sha256Hex(h5.readAttributeString("/spec", "json")));
  EXPECT_EQ(Json::parse(test::readText(out / "summary.json"))["rows"].size(), 1u);
}

TEST_F(JobCrate, IsRefusedWhileRunsAreUnfinished) {
  LiveServer live([](ServerConfig& c) { c.workers = 1; });
  auto client = live.client();
  const auto knob = test::runLengthKnob();
  Json inputs = test::smallInputs();
  const std::int64_t id = test::submit(*client, {{"inputs", inputs}, {"sweep", {{knob.path, {knob.slow}}}}});
  ASSERT_GT(id, 0);
  test::expectProblem(client->Get(("/jobs/" + std::to_string(id) + "/crate").c_str()), 409);
  client->Delete(("/jobs/" + std::to_string(id)).c_str());
  test::waitForJob(*client, id, {"dismissed", "successful", "failed"}, 60);
  test::expectProblem(client->Get("/jobs/999/crate"), 404);
}

}  // namespace
}  // namespace rupture::server
