// XDMF sidecar: every HDF5 reference in the XML must exist in the run file with the stated shape,
// times must match the snapshot attributes, and the layout must follow the verified Xdmf2 template.
#include "io/xdmf_writer.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "io/hdf5_file.hpp"

namespace fs = std::filesystem;
using rupture::io::Hdf5Error;
using rupture::io::Hdf5File;
using rupture::io::writeXdmfSidecar;

namespace {

class XdmfWriterTest : public ::testing::Test {
protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    m_dir = fs::temp_directory_path() /
            ("rupture_xdmf_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
  }
  void TearDown() override { fs::remove_all(m_dir); }
  std::string file(const std::string& name) const { return (m_dir / name).string(); }

  fs::path m_dir;
};

std::vector<double> filled(std::size_t n, double start) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = start + 0.001 * static_cast<double>(i);
  return v;
}

/// One snapshot in the run-file layout the sidecar describes.
void writeSnapshot(Hdf5File& f, const std::string& name, std::size_t n, double time,
                   double strain, bool withRadius) {
  const std::string base = "/snapshots/" + name;
  f.writeDataset(base + "/position", filled(n * 3, 0.0), {n, 3}, "m");
  f.writeDataset(base + "/velocity", filled(n * 3, 1.0), {n, 3}, "m/s");
  f.writeDataset(base + "/stress", filled(n * 9, 1e6), {n, 3, 3}, "Pa");
  f.writeDataset(base + "/damage", filled(n, 0.0), {n}, "1");
  if (withRadius) f.writeDataset(base + "/radius", filled(n, 1e-4), {n}, "m");
  f.setAttribute(base, "time", time);
  f.setAttribute(base, "strain", strain);
}

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::size_t> parseDims(const std::string& text) {
  std::vector<std::size_t> dims;
  std::istringstream in(text);
  for (std::size_t d; in >> d;) dims.push_back(d);
  return dims;
}

/// Tags must nest properly; returns the first problem, or "" for well-nested XML.
std::string nestingProblem(const std::string& xml) {
  static const std::regex tag(R"(<(/?)([A-Za-z]+)[^>]*?(/?)>)");
  std::vector<std::string> open;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), tag); it != std::sregex_iterator();
       ++it) {
    const std::string name = (*it)[2];
    if ((*it)[1] == "/") {
      if (open.empty() || open.back() != name) return "unexpected </" + name + ">";
      open.pop_back();
    } else if ((*it)[3] != "/") {
      open.push_back(name);
    }
  }
  return open.empty() ? "" : "unclosed <" + open.back() + ">";
}

/// Checks every `<DataItem Dimensions="..." ... Format="HDF">file:/path</DataItem>` against the
/// run file; returns how many references were checked.
int checkReferences(const std::string& xml, const std::string& h5Path,
                    const std::string& expectedRef) {
  static const std::regex item(
      R"re(<DataItem Dimensions="([0-9 ]+)"[^>]*Format="HDF">([^<:]+):([^<]+)</DataItem>)re");
  Hdf5File f = Hdf5File::openReadOnly(h5Path);
  int count = 0;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), item);
       it != std::sregex_iterator(); ++it) {
    const std::string dims = (*it)[1];
    const std::string ref = (*it)[2];
    const std::string path = (*it)[3];
    EXPECT_EQ(ref, expectedRef);
    EXPECT_TRUE(f.exists(path)) << path;
    if (f.exists(path)) {
      EXPECT_EQ(f.datasetDims(path), parseDims(dims)) << path;
    }
    ++count;
  }
  return count;
}

}  // namespace

TEST_F(XdmfWriterTest, SidecarReferencesMatchTheRunFile) {
  const std::string h5 = file("run.h5");
  const double times[2] = {0.0, 1.2345678901234567e-5};
  {
    Hdf5File f = Hdf5File::create(h5);
    writeSnapshot(f, "000000", 4, times[0], 0.0, true);
    writeSnapshot(f, "000001", 6, times[1], 1e-3, false);  // a different n, no radius
  }
  const std::string sidecar = file("run.xdmf2");
  writeXdmfSidecar(h5, sidecar);
  const std::string xml = readText(sidecar);

  EXPECT_EQ(nestingProblem(xml), "") << xml;
  EXPECT_NE(xml.find("<Xdmf Version=\"2.0\">"), std::string::npos);
  EXPECT_NE(xml.find("CollectionType=\"Temporal\""), std::string::npos);
  // position, velocity, stress, damage twice, radius once.
  EXPECT_EQ(checkReferences(xml, h5, "run.h5"), 9) << xml;

  // Grids in snapshot order, with their time, point count and attribute kinds.
  static const std::regex grid(
      R"re(<Grid Name="snapshot_(\d+)" GridType="Uniform">\s*<Time Value="([^"]+)"/>\s*)re"
      R"re(<Topology TopologyType="Polyvertex" NumberOfElements="(\d+)" NodesPerElement="1"/>)re");
  std::vector<std::string> names;
  Hdf5File f = Hdf5File::openReadOnly(h5);
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), grid); it != std::sregex_iterator();
       ++it) {
    const std::string name = (*it)[1];
    names.push_back(name);
    const double time = std::strtod((*it)[2].str().c_str(), nullptr);
    EXPECT_EQ(time, f.readAttributeDouble("/snapshots/" + name, "time")) << (*it)[2];
    EXPECT_EQ(std::stoul((*it)[3]), f.datasetDims("/snapshots/" + name + "/position")[0]);
  }
  EXPECT_EQ(names, (std::vector<std::string>{"000000", "000001"})) << xml;

  EXPECT_NE(xml.find("<Geometry GeometryType=\"XYZ\">"), std::string::npos);
  EXPECT_NE(xml.find("Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\""),
            std::string::npos);
  EXPECT_NE(xml.find("Name=\"stress\" AttributeType=\"Tensor\" Center=\"Node\""),
            std::string::npos);
  EXPECT_NE(xml.find("Name=\"damage\" AttributeType=\"Scalar\" Center=\"Node\""),
            std::string::npos);
  EXPECT_NE(xml.find("<DataItem Dimensions=\"6 3 3\""), std::string::npos);  // full 3x3 tensor

  // Written atomically: no temporary file left beside the sidecar.
  for (const auto& entry : fs::directory_iterator(m_dir)) {
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
  }
}

TEST_F(XdmfWriterTest, ReferenceIsRelativeToTheSidecarDirectory) {
  fs::create_directories(m_dir / "data");
  fs::create_directories(m_dir / "view");
  const std::string h5 = file("data/run.h5");
  {
    Hdf5File f = Hdf5File::create(h5);
    writeSnapshot(f, "000000", 3, 0.5, 0.0, true);
  }
  const std::string sidecar = file("view/run.xdmf2");
  writeXdmfSidecar(h5, sidecar);
  const std::string xml = readText(sidecar);
  EXPECT_EQ(checkReferences(xml, h5, "../data/run.h5"), 5) << xml;
}

TEST_F(XdmfWriterTest, RegeneratingReplacesTheSidecar) {
  const std::string h5 = file("run.h5");
  const std::string sidecar = file("run.xdmf2");
  {
    Hdf5File f = Hdf5File::create(h5);
    writeSnapshot(f, "000000", 2, 0.0, 0.0, false);
  }
  writeXdmfSidecar(h5, sidecar);
  {
    Hdf5File f = Hdf5File::openReadWrite(h5);
    writeSnapshot(f, "000001", 2, 1.0, 0.1, false);
  }
  writeXdmfSidecar(h5, sidecar);
  EXPECT_EQ(checkReferences(readText(sidecar), h5, "run.h5"), 8);
}

TEST_F(XdmfWriterTest, EmptySnapshotsAreLeftOut) {
  const std::string h5 = file("run.h5");
  {
    Hdf5File f = Hdf5File::create(h5);
    writeSnapshot(f, "000000", 0, 0.0, 0.0, true);
    writeSnapshot(f, "000001", 2, 1.0, 0.1, true);
  }
  writeXdmfSidecar(h5, file("run.xdmf2"));
  const std::string xml = readText(file("run.xdmf2"));
  EXPECT_EQ(xml.find("snapshot_000000"), std::string::npos) << xml;
  EXPECT_NE(xml.find("snapshot_000001"), std::string::npos) << xml;
  EXPECT_EQ(checkReferences(xml, h5, "run.h5"), 5);
}

TEST_F(XdmfWriterTest, RejectsMalformedRunFiles) {
  const std::string sidecar = file("run.xdmf2");
  {
    Hdf5File f = Hdf5File::create(file("nosnap.h5"));
    f.createGroup("/summary");
  }
  EXPECT_THROW(writeXdmfSidecar(file("nosnap.h5"), sidecar), Hdf5Error);

  {
    Hdf5File f = Hdf5File::create(file("badshape.h5"));
    writeSnapshot(f, "000000", 4, 0.0, 0.0, false);
    f.writeDataset("/snapshots/000000/damage", filled(3, 0.0), {3}, "1");  // n = 3, not 4
  }
  try {
    writeXdmfSidecar(file("badshape.h5"), sidecar);
    FAIL() << "expected Hdf5Error";
  } catch (const Hdf5Error& e) {
    EXPECT_NE(std::string(e.what()).find("/snapshots/000000/damage"), std::string::npos)
        << e.what();
  }

  {
    Hdf5File f = Hdf5File::create(file("notime.h5"));
    f.writeDataset("/snapshots/000000/position", filled(3, 0.0), {1, 3}, "m");
    f.writeDataset("/snapshots/000000/velocity", filled(3, 0.0), {1, 3}, "m/s");
    f.writeDataset("/snapshots/000000/stress", filled(9, 0.0), {1, 3, 3}, "Pa");
    f.writeDataset("/snapshots/000000/damage", filled(1, 0.0), {1}, "1");
  }
  EXPECT_THROW(writeXdmfSidecar(file("notime.h5"), sidecar), Hdf5Error);
  EXPECT_THROW(writeXdmfSidecar(file("absent.h5"), sidecar), Hdf5Error);
  EXPECT_FALSE(fs::exists(sidecar));  // nothing half-written was left behind
}
