// ParaView from the server: the XDMF sidecar served per run names the HDF5 file by its download
// name, every dataset it references exists in that file with the dimensions it states, the bonds
// are line cells over the snapshot's positions, and the tar bundle holds both files unchanged
// (extracted with Python's tarfile, an independent reader).
#include <gtest/gtest.h>

#include <cstdio>
#include <regex>

#include "io/hdf5_file.hpp"
#include "server_test_support.hpp"

namespace rupture::server {
namespace {

using test::getJson;
using test::LiveServer;
namespace fs = std::filesystem;

std::vector<std::size_t> parseDims(const std::string& text) {
  std::vector<std::size_t> dims;
  std::istringstream in(text);
  std::size_t d;
  while (in >> d) dims.push_back(d);
  return dims;
}

void writeFile(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

class ParaviewExport : public ::testing::Test {
protected:
  void SetUp() override {
    if (!test::scenarioAvailable()) GTEST_SKIP() << "dynamic-tension not registered";
    client = live.client();
    jobId = test::submit(*client, Json{{"inputs", test::smallInputs()}});
    ASSERT_GT(jobId, 0);
    const Json done = test::waitForJob(*client, jobId, {"successful", "failed"}, 120);
    ASSERT_EQ(done["status"], "successful") << done.dump();
    base = "/jobs/" + std::to_string(jobId) + "/runs/0";
  }
  std::string get(const std::string& path, int status = 200) {
    auto res = client->Get(path.c_str());
    EXPECT_TRUE(res) << path;
    if (!res) return {};
    EXPECT_EQ(res->status, status) << path << ": " << res->body.substr(0, 300);
    return res->body;
  }
  LiveServer live;
  std::unique_ptr<httplib::Client> client;
  std::int64_t jobId = 0;
  std::string base;
  test::TempDir dir;
};

TEST_F(ParaviewExport, SidecarReferencesExistWithTheirDimensions) {
  const std::string xml = get(base + "/results.xdmf");
  const std::string h5Name = "rupture-job-" + std::to_string(jobId) + "-run-0.h5";
  const fs::path h5 = dir.path() / h5Name;
  writeFile(h5, get(base + "/results"));
  const io::Hdf5File file = io::Hdf5File::openReadOnly(h5.string());

  static const std::regex item(R"re(<DataItem Dimensions="([0-9 ]+)"[^>]*Format="HDF">([^:<]+):([^<]+)</DataItem>)re");
  std::size_t items = 0;
  std::set<std::string> paths;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), item); it != std::sregex_iterator(); ++it) {
    ++items;
    EXPECT_EQ((*it)[2].str(), h5Name) << "the sidecar must name the HDF5 file relatively, by its download name";
    const std::string path = (*it)[3];
    paths.insert(path);
    ASSERT_TRUE(file.exists(path)) << path;
    EXPECT_EQ(file.datasetDims(path), parseDims((*it)[1])) << path;
  }
  const std::size_t snapshots = file.listGroup("/snapshots").size();
  ASSERT_GT(snapshots, 0u);
  EXPECT_GT(items, 4 * snapshots);
  // The bond network: one Polyline grid per snapshot, two nodes per cell, as many cells as bonds.
  const std::size_t bonds = file.datasetDims("/sample/bonds")[0];
  ASSERT_GT(bonds, 0u);
  static const std::regex polyline(R"re(TopologyType="Polyline" NumberOfElements="(\d+)" NodesPerElement="2")re");
  std::size_t lineGrids = 0;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), polyline); it != std::sregex_iterator(); ++it) {
    ++lineGrids;
    EXPECT_EQ(std::stoul((*it)[1]), bonds);
  }
  EXPECT_EQ(lineGrids, snapshots);
  EXPECT_TRUE(paths.count("/sample/bonds"));
  EXPECT_TRUE(paths.count("/snapshots/000000/bond_intact"));
  EXPECT_TRUE(paths.count("/snapshots/000000/bond_equivalent_stress"));
  // Broken bonds are what the crack picture shows: by the last snapshot some have failed.
  const std::string last = file.listGroup("/snapshots").back();
  const auto intact = file.readDatasetInt("/snapshots/" + last + "/bond_intact");
  EXPECT_LT(std::count(intact.begin(), intact.end(), 1), static_cast<long>(bonds));
  const auto load = file.readDatasetDouble("/snapshots/" + last + "/bond_load");
  for (std::size_t b = 0; b < bonds; ++b) {
    if (intact[b] == 1) {
      EXPECT_LT(load[b], 1.0 + 1e-12) << "an intact bond is below its threshold, bond " << b;
    }
  }
}

TEST_F(ParaviewExport, BundleHoldsTheFileAndItsSidecar) {
  const std::string h5 = get(base + "/results");
  const std::string xml = get(base + "/results.xdmf");
  auto res = client->Get((base + "/bundle").c_str());
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200);
  EXPECT_EQ(res->get_header_value("Content-Type"), "application/x-tar");
  EXPECT_EQ(res->body.size() % 512, 0u);
  const fs::path tar = dir.path() / "bundle.tar";
  writeFile(tar, res->body);
  const fs::path out = dir.path() / "out";
  const std::string cmd = "/usr/bin/python3 -c \"import sys, tarfile; t = tarfile.open(sys.argv[1]); "
                          "[print(m.name, m.size) for m in t.getmembers()]; t.extractall(sys.argv[2])\" " +
                          tar.string() + " " + out.string() + " > " + (dir.path() / "list.txt").string();
  ASSERT_EQ(std::system(cmd.c_str()), 0) << "Python's tarfile could not read the bundle";
  const std::string stem = "rupture-job-" + std::to_string(jobId) + "-run-0";
  EXPECT_EQ(test::readText(dir.path() / "list.txt"), stem + "/" + stem + ".h5 " + std::to_string(h5.size()) + "\n" +
                                                         stem + "/" + stem + ".xdmf2 " + std::to_string(xml.size()) + "\n");
  EXPECT_TRUE(test::readText(out / stem / (stem + ".h5")) == h5);
  EXPECT_EQ(test::readText(out / stem / (stem + ".xdmf2")), xml);
}

TEST_F(ParaviewExport, CliWritesASidecarPerRunOfAMergedJobFile) {
  const fs::path merged = dir.path() / "job.h5";
  writeFile(merged, get("/jobs/" + std::to_string(jobId) + "/results"));
  const std::string cmd = std::string(RUPTURE_CLI) + " xdmf " + merged.string() + " > " + (dir.path() / "out.txt").string();
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const fs::path sidecar = dir.path() / "job.run-0.xdmf2";
  EXPECT_EQ(test::readText(dir.path() / "out.txt"), sidecar.string() + "\n");
  const std::string xml = test::readText(sidecar);
  const io::Hdf5File file = io::Hdf5File::openReadOnly(merged.string());
  static const std::regex item(R"re(<DataItem Dimensions="([0-9 ]+)"[^>]*Format="HDF">job\.h5:([^<]+)</DataItem>)re");
  std::size_t items = 0;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), item); it != std::sregex_iterator(); ++it, ++items) {
    const std::string path = (*it)[2];
    EXPECT_EQ(path.rfind("/run-0/", 0), 0u) << path;
    ASSERT_TRUE(file.exists(path)) << path;
    EXPECT_EQ(file.datasetDims(path), parseDims((*it)[1])) << path;
  }
  EXPECT_GT(items, 8u);
  EXPECT_NE(xml.find("/run-0/sample/bonds"), std::string::npos);
}

TEST_F(ParaviewExport, UnknownRunIs404AndNotReadyIsProblem) {
  auto res = client->Get(("/jobs/" + std::to_string(jobId) + "/runs/7/results.xdmf").c_str());
  test::expectProblem(res, 404, "run");
  res = client->Get(("/jobs/" + std::to_string(jobId) + "/runs/7/bundle").c_str());
  test::expectProblem(res, 404, "run");
  const Json doc = getJson(*client, base);
  std::set<std::string> hrefs;
  for (const auto& l : doc["links"]) hrefs.insert(l["href"].get<std::string>());
  EXPECT_TRUE(hrefs.count(base + "/results.xdmf"));
  EXPECT_TRUE(hrefs.count(base + "/bundle"));
}

}  // namespace
}  // namespace rupture::server
