// Hdf5File: round trips of every attribute and dataset type, the storage layout it promises
// (chunking + shuffle + deflate, checked through the C API), groups, merging and error reporting.
#include "io/hdf5_file.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <hdf5.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

namespace fs = std::filesystem;
using rupture::io::Hdf5Error;
using rupture::io::Hdf5File;

namespace {

/// A fresh directory per test, removed afterwards.
class Hdf5FileTest : public ::testing::Test {
protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    m_dir = fs::temp_directory_path() /
            ("rupture_io_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
  }
  void TearDown() override { fs::remove_all(m_dir); }
  std::string file(const std::string& name) const { return (m_dir / name).string(); }

  fs::path m_dir;
};

std::vector<double> ramp(std::size_t n) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = 0.5 * static_cast<double>(i) - 3.0;
  return v;
}

/// Every attribute of the tree at root (objects reached through links, recursively), keyed
/// "<path below root>@<name>", the value rendered with its kind. Trees with link cycles loop.
std::map<std::string, std::string> attributeTree(const Hdf5File& f, const std::string& root,
                                                 const std::string& below = "") {
  std::map<std::string, std::string> out;
  const std::string path = root + below;
  for (const std::string& name : f.listAttributes(path.empty() ? "/" : path)) {
    const std::string at = path.empty() ? "/" : path;
    std::ostringstream value;
    value.precision(17);
    try {
      value << "string " << f.readAttributeString(at, name);
    } catch (const Hdf5Error&) {
      try {
        value << "int " << f.readAttributeInt(at, name);
      } catch (const Hdf5Error&) {
        try {
          value << "double " << f.readAttributeDouble(at, name);
        } catch (const Hdf5Error&) {
          value << "not a scalar";  // compared through the C API where it matters
        }
      }
    }
    out[below + "@" + name] = value.str();
  }
  std::vector<std::string> children;
  try {
    children = f.listGroup(path.empty() ? "/" : path);
  } catch (const Hdf5Error&) {  // a dataset
  }
  for (const std::string& child : children) {
    if (!f.exists(path + "/" + child)) continue;  // dangling link
    out.merge(attributeTree(f, root, below + "/" + child));
  }
  return out;
}

/// Address of the object at path, through the C API (same address: same, shared object).
haddr_t objectAddress(const std::string& filePath, const std::string& objPath) {
  const hid_t fid = H5Fopen(filePath.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(fid, 0);
  H5O_info_t info{};
  EXPECT_GE(H5Oget_info_by_name2(fid, objPath.c_str(), &info, H5O_INFO_BASIC, H5P_DEFAULT), 0);
  H5Fclose(fid);
  return info.addr;
}

}  // namespace

TEST_F(Hdf5FileTest, AttributesRoundTripEveryType) {
  const std::string path = file("attrs.h5");
  {
    Hdf5File f = Hdf5File::create(path);
    f.createGroup("/summary");
    f.setAttribute("/", "dt", 1.25e-9);
    f.setAttribute("/", "steps", std::int64_t{-9'000'000'000'000});
    f.setAttribute("/", "big", std::numeric_limits<std::int64_t>::max());
    f.setAttribute("/summary", "material", std::string("σ_c ≥ 2 µm, ε"));
    f.setAttribute("/summary", "empty", std::string());
    // Overwrite with a different type: the old attribute must be replaced, not kept.
    f.setAttribute("/summary", "peak", 1.0);
    f.setAttribute("/summary", "peak", std::string("n/a"));
    f.setAttribute("/summary", "peak", 3.5e8);
  }
  Hdf5File f = Hdf5File::openReadOnly(path);
  EXPECT_EQ(f.readAttributeDouble("/", "dt"), 1.25e-9);
  EXPECT_EQ(f.readAttributeInt("/", "steps"), -9'000'000'000'000);
  EXPECT_EQ(f.readAttributeInt("/", "big"), std::numeric_limits<std::int64_t>::max());
  EXPECT_EQ(f.readAttributeDouble("/", "steps"), -9.0e12);  // integers convert to double
  EXPECT_EQ(f.readAttributeString("/summary", "material"), "σ_c ≥ 2 µm, ε");
  EXPECT_EQ(f.readAttributeString("/summary", "empty"), "");
  EXPECT_EQ(f.readAttributeDouble("/summary", "peak"), 3.5e8);
  EXPECT_TRUE(f.hasAttribute("/summary", "peak"));
  EXPECT_FALSE(f.hasAttribute("/summary", "nope"));
  EXPECT_EQ(f.listAttributes("/"), (std::vector<std::string>{"big", "dt", "steps"}));
  EXPECT_EQ(f.listAttributes("/summary"), (std::vector<std::string>{"empty", "material", "peak"}));
  // Truncating a double to an integer, or reading a number as text, is refused.
  EXPECT_THROW(f.readAttributeInt("/", "dt"), Hdf5Error);
  EXPECT_THROW(f.readAttributeString("/", "dt"), Hdf5Error);
  EXPECT_THROW(f.readAttributeDouble("/summary", "material"), Hdf5Error);
  EXPECT_THROW(f.readAttributeDouble("/", "missing"), Hdf5Error);
  EXPECT_THROW(f.hasAttribute("/no/such/group", "x"), Hdf5Error);
}

TEST_F(Hdf5FileTest, StringAttributeIsVariableLengthUtf8) {
  const std::string path = file("vlen.h5");
  {
    Hdf5File f = Hdf5File::create(path);
    f.setAttribute("/", "name", std::string("rupture"));
  }
  hid_t fid = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(fid, 0);
  hid_t attr = H5Aopen(fid, "name", H5P_DEFAULT);
  ASSERT_GE(attr, 0);
  hid_t type = H5Aget_type(attr);
  EXPECT_EQ(H5Tget_class(type), H5T_STRING);
  EXPECT_GT(H5Tis_variable_str(type), 0);
  EXPECT_EQ(H5Tget_cset(type), H5T_CSET_UTF8);
  H5Tclose(type);
  H5Aclose(attr);
  H5Fclose(fid);
}

TEST_F(Hdf5FileTest, ReadsFixedLengthStringAttribute) {
  // Written by other tools (H5MD's author name is fixed-length): must read back without padding.
  const std::string path = file("fixed.h5");
  {
    hid_t fid = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    ASSERT_GE(fid, 0);
    hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, 16);
    H5Tset_strpad(type, H5T_STR_NULLPAD);
    hid_t space = H5Screate(H5S_SCALAR);
    hid_t attr = H5Acreate2(fid, "author", type, space, H5P_DEFAULT, H5P_DEFAULT);
    char text[16] = "Ada";
    ASSERT_GE(H5Awrite(attr, type, text), 0);
    H5Aclose(attr);
    H5Sclose(space);
    H5Tclose(type);
    H5Fclose(fid);
  }
  Hdf5File f = Hdf5File::openReadOnly(path);
  EXPECT_EQ(f.readAttributeString("/", "author"), "Ada");
}

TEST_F(Hdf5FileTest, DatasetsRoundTripEveryTypeAndShape) {
  const std::string path = file("data.h5");
  const std::vector<double> positions = ramp(4 * 3);
  const std::vector<double> stress = ramp(2 * 3 * 3);
  const std::vector<std::int32_t> ids = {7, -2, 0, std::numeric_limits<std::int32_t>::max(),
                                         std::numeric_limits<std::int32_t>::min()};
  const std::vector<std::uint8_t> flags = {0, 1, 255, 3, 128, 9};
  {
    Hdf5File f = Hdf5File::create(path);
    f.writeDataset("/particles/position", positions, {4, 3}, "m");  // parents created
    f.writeDataset("/particles/stress", stress, {2, 3, 3}, "Pa");
    f.writeDataset("/particles/id", ids, {5}, "1");
    f.writeDataset("/particles/flags", flags, {2, 3}, "1");
  }
  Hdf5File f = Hdf5File::openReadOnly(path);
  EXPECT_EQ(f.readDatasetDouble("/particles/position"), positions);
  EXPECT_EQ(f.readDatasetDouble("/particles/stress"), stress);
  EXPECT_EQ(f.datasetDims("/particles/position"), (std::vector<std::size_t>{4, 3}));
  EXPECT_EQ(f.datasetDims("/particles/stress"), (std::vector<std::size_t>{2, 3, 3}));
  EXPECT_EQ(f.datasetDims("/particles/id"), (std::vector<std::size_t>{5}));
  EXPECT_EQ(f.datasetDims("/particles/flags"), (std::vector<std::size_t>{2, 3}));

  const std::vector<std::int64_t> idsBack = f.readDatasetInt("/particles/id");
  EXPECT_EQ(idsBack, std::vector<std::int64_t>(ids.begin(), ids.end()));
  const std::vector<std::int64_t> flagsBack = f.readDatasetInt("/particles/flags");
  EXPECT_EQ(flagsBack, std::vector<std::int64_t>(flags.begin(), flags.end()));  // unsigned kept
  const std::vector<double> idsAsDouble = f.readDatasetDouble("/particles/id");
  EXPECT_EQ(idsAsDouble, std::vector<double>(ids.begin(), ids.end()));

  EXPECT_EQ(f.readAttributeString("/particles/position", "unit"), "m");
  EXPECT_EQ(f.readAttributeString("/particles/stress", "unit"), "Pa");
  EXPECT_EQ(f.readAttributeString("/particles/id", "unit"), "1");
  EXPECT_EQ(f.listAttributes("/particles/flags"), (std::vector<std::string>{"unit"}));

  EXPECT_THROW(f.readDatasetInt("/particles/position"), Hdf5Error);  // would truncate
  EXPECT_THROW(f.readDatasetDouble("/particles/missing"), Hdf5Error);
  EXPECT_THROW(f.datasetDims("/particles"), Hdf5Error);  // a group, not a dataset
}

TEST_F(Hdf5FileTest, EmptyDatasetsAreWritable) {
  const std::string path = file("empty.h5");
  {
    Hdf5File f = Hdf5File::create(path);
    f.writeDataset("/a", std::vector<double>{}, {0}, "m");
    f.writeDataset("/b", std::vector<double>{}, {0, 3}, "m/s");
    f.writeDataset("/c", std::vector<std::int32_t>{}, {0, 3, 3}, "1");
    f.writeDataset("/d", std::vector<std::uint8_t>{}, {4, 0}, "1");
  }
  Hdf5File f = Hdf5File::openReadOnly(path);
  EXPECT_EQ(f.datasetDims("/a"), (std::vector<std::size_t>{0}));
  EXPECT_EQ(f.datasetDims("/b"), (std::vector<std::size_t>{0, 3}));
  EXPECT_EQ(f.datasetDims("/c"), (std::vector<std::size_t>{0, 3, 3}));
  EXPECT_EQ(f.datasetDims("/d"), (std::vector<std::size_t>{4, 0}));
  EXPECT_TRUE(f.readDatasetDouble("/a").empty());
  EXPECT_TRUE(f.readDatasetDouble("/b").empty());
  EXPECT_TRUE(f.readDatasetInt("/c").empty());
  EXPECT_EQ(f.readAttributeString("/b", "unit"), "m/s");
}

TEST_F(Hdf5FileTest, RejectsShapeMismatchAndReplacesDatasets) {
  Hdf5File f = Hdf5File::create(file("shape.h5"));
  EXPECT_THROW(f.writeDataset("/x", ramp(5), {2, 3}, "m"), Hdf5Error);
  EXPECT_THROW(f.writeDataset("/x", ramp(1), {}, "m"), Hdf5Error);
  EXPECT_FALSE(f.exists("/x"));

  f.writeDataset("/x", ramp(6), {2, 3}, "m");
  f.writeDataset("/x", ramp(4), {4}, "Pa");  // replaced with a new shape and unit
  EXPECT_EQ(f.datasetDims("/x"), (std::vector<std::size_t>{4}));
  EXPECT_EQ(f.readDatasetDouble("/x"), ramp(4));
  EXPECT_EQ(f.readAttributeString("/x", "unit"), "Pa");

  f.createGroup("/g/h");
  EXPECT_THROW(f.writeDataset("/g", ramp(1), {1}, "m"), Hdf5Error);  // never drops a group
  EXPECT_TRUE(f.exists("/g/h"));
}

TEST_F(Hdf5FileTest, NonEmptyDatasetIsChunkedShuffledAndDeflated) {
  const std::string path = file("layout.h5");
  const std::size_t n = 20000;  // 480 kB of doubles: more than one chunk
  std::vector<double> values(n * 3, 1.0);  // compressible
  {
    Hdf5File f = Hdf5File::create(path);
    f.writeDataset("/v", values, {n, 3}, "m");
    f.writeDataset("/empty", std::vector<double>{}, {0, 3}, "m");
  }
  hid_t fid = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(fid, 0);
  hid_t dset = H5Dopen2(fid, "/v", H5P_DEFAULT);
  ASSERT_GE(dset, 0);
  hid_t dcpl = H5Dget_create_plist(dset);
  ASSERT_GE(dcpl, 0);

  EXPECT_EQ(H5Pget_layout(dcpl), H5D_CHUNKED);
  hsize_t chunk[2] = {0, 0};
  ASSERT_EQ(H5Pget_chunk(dcpl, 2, chunk), 2);
  EXPECT_GE(chunk[0], 1u);
  EXPECT_LT(chunk[0], n);  // split along the particles
  EXPECT_EQ(chunk[1], 3u);

  ASSERT_EQ(H5Pget_nfilters(dcpl), 2);
  unsigned flags = 0;
  std::size_t nValues = 1;
  unsigned level = 0;
  unsigned config = 0;
  EXPECT_EQ(H5Pget_filter2(dcpl, 0, &flags, &nValues, &level, 0, nullptr, &config),
            H5Z_FILTER_SHUFFLE);  // shuffle must run before deflate
  nValues = 1;
  level = 0;
  EXPECT_EQ(H5Pget_filter2(dcpl, 1, &flags, &nValues, &level, 0, nullptr, &config),
            H5Z_FILTER_DEFLATE);
  EXPECT_EQ(nValues, 1u);
  EXPECT_EQ(level, 4u);
  // The filters really ran: constant data shrinks far below its raw size.
  EXPECT_LT(H5Dget_storage_size(dset), n * 3 * sizeof(double) / 10);
  H5Pclose(dcpl);
  H5Dclose(dset);

  // The empty dataset is chunked and extendible along its first dimension.
  dset = H5Dopen2(fid, "/empty", H5P_DEFAULT);
  ASSERT_GE(dset, 0);
  dcpl = H5Dget_create_plist(dset);
  EXPECT_EQ(H5Pget_layout(dcpl), H5D_CHUNKED);
  hid_t space = H5Dget_space(dset);
  hsize_t dims[2] = {9, 9};
  hsize_t maxDims[2] = {0, 0};
  ASSERT_EQ(H5Sget_simple_extent_dims(space, dims, maxDims), 2);
  EXPECT_EQ(dims[0], 0u);
  EXPECT_EQ(maxDims[0], H5S_UNLIMITED);
  H5Sclose(space);
  H5Pclose(dcpl);
  H5Dclose(dset);
  H5Fclose(fid);
}

TEST_F(Hdf5FileTest, GroupsExistAndListSorted) {
  Hdf5File f = Hdf5File::create(file("groups.h5"));
  f.createGroup("/a/b/c");  // intermediates
  f.createGroup("/a/b/c");  // again: fine
  f.createGroup("/a/zeta");
  f.createGroup("/a/alpha");
  f.writeDataset("/a/mid", ramp(3), {3}, "m");

  EXPECT_TRUE(f.exists("/"));
  EXPECT_TRUE(f.exists("/a"));
  EXPECT_TRUE(f.exists("/a/b/c"));
  EXPECT_TRUE(f.exists("/a/mid"));
  EXPECT_FALSE(f.exists("/a/x"));
  EXPECT_FALSE(f.exists("/a/x/y"));    // a missing middle level is "no", not an error
  EXPECT_FALSE(f.exists("/a/mid/y"));  // a dataset in the middle too
  EXPECT_FALSE(f.exists(""));

  EXPECT_EQ(f.listGroup("/a"), (std::vector<std::string>{"alpha", "b", "mid", "zeta"}));
  EXPECT_EQ(f.listGroup("/"), (std::vector<std::string>{"a"}));
  EXPECT_TRUE(f.listGroup("/a/b/c").empty());
  EXPECT_THROW(f.listGroup("/a/mid"), Hdf5Error);
  EXPECT_THROW(f.listGroup("/nope"), Hdf5Error);
  EXPECT_THROW(f.createGroup("/a/mid"), Hdf5Error);  // exists as a dataset
}

TEST_F(Hdf5FileTest, DanglingSoftLinkDoesNotExist) {
  const std::string path = file("dangling.h5");
  Hdf5File::create(path).close();
  hid_t fid = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(fid, 0);
  ASSERT_GE(H5Lcreate_soft("/nowhere", fid, "/alias", H5P_DEFAULT, H5P_DEFAULT), 0);
  H5Fclose(fid);
  Hdf5File f = Hdf5File::openReadOnly(path);
  EXPECT_FALSE(f.exists("/alias"));  // the link is there, but nothing can be read through it
  EXPECT_EQ(f.listGroup("/"), (std::vector<std::string>{"alias"}));
}

TEST_F(Hdf5FileTest, CopyFileIntoIsSelfContained) {
  const std::string source = file("run1.h5");
  const std::string merged = file("merged.h5");
  {
    Hdf5File s = Hdf5File::create(source);
    s.setAttribute("/", "scenario", std::string("dynamic-tension"));
    s.setAttribute("/", "seed", std::int64_t{42});
    s.setAttribute("/", "rate", 250.0);
    s.writeDataset("/snapshots/000000/position", ramp(6), {2, 3}, "m");
    s.setAttribute("/snapshots/000000", "time", 1e-6);
    s.writeDataset("/summary/ids", std::vector<std::int32_t>{1, 2, 3}, {3}, "1");
  }
  {
    // Soft link with an absolute target: expanded, so it cannot end up pointing into the merged
    // file's own root.
    hid_t fid = H5Fopen(source.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(fid, 0);
    ASSERT_GE(H5Lcreate_soft("/summary/ids", fid, "/ids_alias", H5P_DEFAULT, H5P_DEFAULT), 0);
    H5Fclose(fid);
  }
  {
    Hdf5File m = Hdf5File::create(merged);
    m.setAttribute("/", "kind", std::string("sweep"));
    m.copyFileInto(source, "/runs/run1");
    EXPECT_THROW(m.copyFileInto(source, "/runs/run1"), Hdf5Error);  // destination exists
    EXPECT_THROW(m.copyFileInto(merged, "/self"), Hdf5Error);
  }
  ASSERT_TRUE(fs::remove(source));

  Hdf5File m = Hdf5File::openReadOnly(merged);
  EXPECT_EQ(m.listGroup("/runs/run1"),
            (std::vector<std::string>{"ids_alias", "snapshots", "summary"}));
  EXPECT_EQ(m.readDatasetDouble("/runs/run1/snapshots/000000/position"), ramp(6));
  EXPECT_EQ(m.readAttributeString("/runs/run1/snapshots/000000/position", "unit"), "m");
  EXPECT_EQ(m.readAttributeDouble("/runs/run1/snapshots/000000", "time"), 1e-6);
  EXPECT_EQ(m.readDatasetInt("/runs/run1/summary/ids"), (std::vector<std::int64_t>{1, 2, 3}));
  EXPECT_EQ(m.readDatasetInt("/runs/run1/ids_alias"), (std::vector<std::int64_t>{1, 2, 3}));
  // The source's root attributes now sit on the destination group; the merged root keeps its own.
  EXPECT_EQ(m.readAttributeString("/runs/run1", "scenario"), "dynamic-tension");
  EXPECT_EQ(m.readAttributeInt("/runs/run1", "seed"), 42);
  EXPECT_EQ(m.readAttributeDouble("/runs/run1", "rate"), 250.0);
  EXPECT_EQ(m.listAttributes("/"), (std::vector<std::string>{"kind"}));
}

// Regression: H5Ocopy of an object with more than 8 attributes (dense storage) including
// variable-length strings segfaults in Debian's HDF5 1.10.8, and the engine's /summary group is
// such an object. A regression crashes this test binary.
TEST_F(Hdf5FileTest, CopyFileIntoKeepsManyAttributesWithStrings) {
  const std::string source = file("run.h5");
  const std::string merged = file("merged.h5");
  {
    Hdf5File s = Hdf5File::create(source);
    s.createGroup("/summary");
    for (int i = 0; i < 12; ++i) {  // 4 of each kind, interleaved
      const std::string name = "value_" + std::to_string(i);
      if (i % 3 == 0) s.setAttribute("/summary", name, "text " + std::to_string(i) + " µm");
      if (i % 3 == 1) s.setAttribute("/summary", name, 0.1 * i);
      if (i % 3 == 2) s.setAttribute("/summary", name, std::int64_t{-1'000'000'000'000} * i);
      s.setAttribute("/", name, std::string(i, 'r'));  // the root too, with 12 strings
    }
    s.setAttribute("/summary", "empty", std::string());
    s.writeDataset("/summary/series", ramp(5), {5}, "Pa");
    for (int i = 0; i < 10; ++i) {
      s.setAttribute("/summary/series", "label_" + std::to_string(i), "series " + std::to_string(i));
      s.setAttribute("/summary/series", "scale_" + std::to_string(i), 2.0 * i);
    }
    s.writeDataset("/sample/ids", std::vector<std::int32_t>{4, 5}, {2}, "1");
  }
  {
    hid_t fid = H5Fopen(source.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(fid, 0);
    // A fixed-length string and a non-scalar attribute, as other writers (h5py, H5MD) make them.
    hid_t fixed = H5Tcopy(H5T_C_S1);
    H5Tset_size(fixed, 8);
    hid_t scalar = H5Screate(H5S_SCALAR);
    hid_t attr = H5Acreate_by_name(fid, "/summary", "author", fixed, scalar, H5P_DEFAULT,
                                   H5P_DEFAULT, H5P_DEFAULT);
    ASSERT_GE(H5Awrite(attr, fixed, "Ada\0\0\0\0\0"), 0);
    H5Aclose(attr);
    const hsize_t three = 3;
    hid_t vector = H5Screate_simple(1, &three, nullptr);
    const double box[3] = {1.0, 2.0, 3.5};
    attr = H5Acreate_by_name(fid, "/sample", "box", H5T_IEEE_F64LE, vector, H5P_DEFAULT,
                             H5P_DEFAULT, H5P_DEFAULT);
    ASSERT_GE(H5Awrite(attr, H5T_NATIVE_DOUBLE, box), 0);
    H5Aclose(attr);
    H5Sclose(vector);
    H5Sclose(scalar);
    H5Tclose(fixed);
    // A dangling soft link: nothing to copy attributes from, and no reason to fail.
    ASSERT_GE(H5Lcreate_soft("/nowhere", fid, "/sample/lost", H5P_DEFAULT, H5P_DEFAULT), 0);
    H5Fclose(fid);
  }
  {
    Hdf5File m = Hdf5File::create(merged);
    m.copyFileInto(source, "/run-0");
    m.copyFileInto(source, "/runs/run-1");
  }

  Hdf5File s = Hdf5File::openReadOnly(source);
  Hdf5File m = Hdf5File::openReadOnly(merged);
  const auto expected = attributeTree(s, "");
  EXPECT_EQ(expected.size(), 12u + 13u + 21u + 1u + 1u + 1u);  // + ids@unit, author, box
  EXPECT_EQ(attributeTree(m, "/run-0"), expected);
  EXPECT_EQ(attributeTree(m, "/runs/run-1"), expected);
  EXPECT_EQ(m.readAttributeString("/run-0/summary", "value_3"), "text 3 µm");
  EXPECT_EQ(m.readAttributeDouble("/run-0/summary", "value_4"), 0.1 * 4);
  EXPECT_EQ(m.readAttributeInt("/run-0/summary", "value_5"), std::int64_t{-5'000'000'000'000});
  EXPECT_EQ(m.readAttributeString("/run-0/summary", "author"), "Ada");
  EXPECT_EQ(m.readAttributeString("/run-0/summary/series", "unit"), "Pa");
  EXPECT_EQ(m.readDatasetDouble("/run-0/summary/series"), ramp(5));
  EXPECT_EQ(m.readAttributeString("/runs/run-1", "value_11"), std::string(11, 'r'));
  EXPECT_EQ(m.listAttributes("/"), std::vector<std::string>{});
  {
    hid_t fid = H5Fopen(merged.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(fid, 0);
    hid_t attr = H5Aopen_by_name(fid, "/run-0/sample", "box", H5P_DEFAULT, H5P_DEFAULT);
    ASSERT_GE(attr, 0);
    hid_t space = H5Aget_space(attr);
    EXPECT_EQ(H5Sget_simple_extent_npoints(space), 3);
    double box[3] = {};
    EXPECT_GE(H5Aread(attr, H5T_NATIVE_DOUBLE, box), 0);
    EXPECT_EQ(box[2], 3.5);
    H5Sclose(space);
    H5Aclose(attr);
    H5Fclose(fid);
  }
}

TEST_F(Hdf5FileTest, CopyFileIntoKeepsHardLinksSharedAndSurvivesCycles) {
  const std::string source = file("run.h5");
  const std::string merged = file("merged.h5");
  {
    Hdf5File s = Hdf5File::create(source);
    s.writeDataset("/g/data", ramp(3), {3}, "m");
    s.setAttribute("/g", "name", std::string("g"));
  }
  {
    hid_t fid = H5Fopen(source.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(fid, 0);
    ASSERT_GE(H5Lcreate_hard(fid, "/g/data", fid, "/alias", H5P_DEFAULT, H5P_DEFAULT), 0);
    ASSERT_GE(H5Lcreate_hard(fid, "/g", fid, "/g/loop", H5P_DEFAULT, H5P_DEFAULT), 0);
    H5Fclose(fid);
  }
  {
    Hdf5File m = Hdf5File::create(merged);
    m.copyFileInto(source, "/run");
    EXPECT_EQ(m.readAttributeString("/run/alias", "unit"), "m");
    EXPECT_EQ(m.readAttributeString("/run/g/loop/loop", "name"), "g");
    EXPECT_EQ(m.listAttributes("/run/g"), std::vector<std::string>{"name"});
  }
  EXPECT_EQ(objectAddress(merged, "/run/alias"), objectAddress(merged, "/run/g/data"));
  EXPECT_EQ(objectAddress(merged, "/run/g/loop"), objectAddress(merged, "/run/g"));
}

TEST_F(Hdf5FileTest, CopyFileIntoRefusesReferenceAttributesAndLeavesNothing) {
  const std::string source = file("run.h5");
  {
    Hdf5File s = Hdf5File::create(source);
    s.writeDataset("/g/data", ramp(3), {3}, "m");
  }
  {
    hid_t fid = H5Fopen(source.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(fid, 0);
    hobj_ref_t ref{};
    ASSERT_GE(H5Rcreate(&ref, fid, "/g/data", H5R_OBJECT, -1), 0);
    hid_t scalar = H5Screate(H5S_SCALAR);
    hid_t attr = H5Acreate_by_name(fid, "/g", "target", H5T_STD_REF_OBJ, scalar, H5P_DEFAULT,
                                   H5P_DEFAULT, H5P_DEFAULT);
    ASSERT_GE(H5Awrite(attr, H5T_STD_REF_OBJ, &ref), 0);
    H5Aclose(attr);
    H5Sclose(scalar);
    H5Fclose(fid);
  }
  Hdf5File m = Hdf5File::create(file("merged.h5"));
  try {
    m.copyFileInto(source, "/runs/run");
    FAIL() << "expected Hdf5Error";
  } catch (const Hdf5Error& e) {
    EXPECT_NE(std::string(e.what()).find("/g@target"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(m.exists("/runs/run"));
}

// A real engine result, when one is at hand (writing one takes about a minute):
//   rupture run examples/dynamic-tension-small.json -o run.h5
//   RUPTURE_TEST_RUN_FILE=$PWD/run.h5 tests/io_tests
TEST_F(Hdf5FileTest, CopyFileIntoCopiesEngineRunFile) {
  // A real run file from the CLI: the small example at 1e7 /s with the linear field (no
  // preliminary run), well under a second.
  std::ifstream example(std::string(RUPTURE_SOURCE_DIR) + "/examples/dynamic-tension-small.json");
  nlohmann::json spec = nlohmann::json::parse(example);
  spec["loading"] = {{"strain_rate", 1e7}, {"initial_velocity", "VL"}};
  const std::string specPath = file("spec.json");
  std::ofstream(specPath) << spec.dump();
  const std::string runPath = file("run.h5");
  ASSERT_EQ(std::system((std::string(RUPTURE_CLI) + " run " + specPath + " -o " + runPath + " > /dev/null 2>&1").c_str()), 0);
  const char* run = runPath.c_str();
  const std::string merged = file("merged.h5");
  {
    Hdf5File m = Hdf5File::create(merged);
    m.copyFileInto(run, "/run-0");
  }
  Hdf5File s = Hdf5File::openReadOnly(run);
  Hdf5File m = Hdf5File::openReadOnly(merged);
  const auto expected = attributeTree(s, "");
  EXPECT_GT(expected.count("/summary@wall_time_s"), 0u);
  EXPECT_EQ(attributeTree(m, "/run-0"), expected);
}

TEST_F(Hdf5FileTest, CopyFileIntoReportsMissingSource) {
  Hdf5File m = Hdf5File::create(file("merged.h5"));
  const std::string missing = file("not-there.h5");
  try {
    m.copyFileInto(missing, "/runs/x");
    FAIL() << "expected Hdf5Error";
  } catch (const Hdf5Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
  EXPECT_FALSE(m.exists("/runs/x"));
}

TEST_F(Hdf5FileTest, OpeningMissingFileThrowsWithPath) {
  const std::string missing = file("missing/run.h5");
  for (auto open : {&Hdf5File::openReadOnly, &Hdf5File::openReadWrite}) {
    try {
      (void)open(missing);
      FAIL() << "expected Hdf5Error";
    } catch (const Hdf5Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(missing), std::string::npos) << what;
      EXPECT_NE(what.find("No such file"), std::string::npos) << what;  // the HDF5 detail
    }
  }
  EXPECT_THROW(Hdf5File::create(file("missing/dir/run.h5")), Hdf5Error);
}

TEST_F(Hdf5FileTest, ErrorsNameTheObject) {
  Hdf5File f = Hdf5File::create(file("names.h5"));
  try {
    (void)f.readDatasetDouble("/deep/missing");
    FAIL() << "expected Hdf5Error";
  } catch (const Hdf5Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("/deep/missing"), std::string::npos) << what;
    EXPECT_NE(what.find(f.path()), std::string::npos) << what;
  }
}

TEST_F(Hdf5FileTest, ReadOnlyFileRefusesWrites) {
  const std::string path = file("ro.h5");
  Hdf5File::create(path).close();
  Hdf5File f = Hdf5File::openReadOnly(path);
  EXPECT_THROW(f.createGroup("/g"), Hdf5Error);
  EXPECT_THROW(f.setAttribute("/", "x", 1.0), Hdf5Error);
  EXPECT_THROW(f.writeDataset("/d", ramp(2), {2}, "m"), Hdf5Error);
}

TEST_F(Hdf5FileTest, ReadWriteReopenAppends) {
  const std::string path = file("rw.h5");
  {
    Hdf5File f = Hdf5File::create(path);
    f.writeDataset("/a", ramp(2), {2}, "m");
  }
  {
    Hdf5File f = Hdf5File::openReadWrite(path);
    f.writeDataset("/b", ramp(3), {3}, "m");
    f.setAttribute("/a", "note", std::string("kept"));
    f.flush();
  }
  Hdf5File f = Hdf5File::openReadOnly(path);
  EXPECT_EQ(f.readDatasetDouble("/a"), ramp(2));
  EXPECT_EQ(f.readDatasetDouble("/b"), ramp(3));
  EXPECT_EQ(f.readAttributeString("/a", "note"), "kept");
}

TEST_F(Hdf5FileTest, MoveAndCloseAreSafe) {
  const std::string path = file("move.h5");
  Hdf5File a = Hdf5File::create(path);
  a.createGroup("/g");
  Hdf5File b = std::move(a);
  EXPECT_EQ(b.path(), path);
  EXPECT_TRUE(b.exists("/g"));
  EXPECT_NO_THROW(a.close());  // moved-from: nothing to close  NOLINT(bugprone-use-after-move)
  Hdf5File c = Hdf5File::create(file("other.h5"));
  c = std::move(b);  // closes other.h5, takes over move.h5
  EXPECT_EQ(c.path(), path);
  c.close();
  c.close();  // idempotent
  EXPECT_THROW(c.exists("/g"), Hdf5Error);
  EXPECT_THROW(c.flush(), Hdf5Error);
  // Both files were really closed: truncating them again is allowed.
  EXPECT_NO_THROW(Hdf5File::create(path));
  EXPECT_NO_THROW(Hdf5File::create(file("other.h5")));
}

TEST_F(Hdf5FileTest, WorkerThreadsUseOwnFilesAndStayQuiet) {
  constexpr int kThreads = 4;
  constexpr int kFilesPerThread = 10;
  std::atomic<int> failures{0};
  std::vector<std::thread> threads;
  ::testing::internal::CaptureStderr();
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      try {
        for (int i = 0; i < kFilesPerThread; ++i) {
          const std::string path = file(std::to_string(t) + "_" + std::to_string(i) + ".h5");
          {
            Hdf5File f = Hdf5File::create(path);
            f.writeDataset("/v", ramp(300), {100, 3}, "m");
            f.setAttribute("/", "thread", std::int64_t{t});
          }
          Hdf5File f = Hdf5File::openReadOnly(path);
          if (f.readDatasetDouble("/v") != ramp(300) || f.readAttributeInt("/", "thread") != t) {
            ++failures;
          }
          // A failure in a fresh thread must become an exception, not an HDF5 stack dump.
          try {
            (void)f.readDatasetDouble("/missing");
            ++failures;
          } catch (const Hdf5Error&) {
          }
        }
      } catch (...) {
        ++failures;
      }
    });
  }
  for (auto& th : threads) th.join();
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(failures.load(), 0);
  EXPECT_EQ(printed.find("HDF5-DIAG"), std::string::npos) << printed;
}

TEST_F(Hdf5FileTest, BufferedFilesAreWholeOnDiskOnlyOnceClosed) {
  // Built in memory, written at close: the same content as a file written in place.
  const std::string path = file("buffered.h5");
  std::vector<double> values(100'000);
  for (std::size_t k = 0; k < values.size(); ++k) values[k] = 0.5 * static_cast<double>(k);
  {
    Hdf5File f = Hdf5File::createBuffered(path);
    f.writeDataset("/a/values", values, {values.size()}, "m");
    f.setAttribute("/a", "label", std::string("buffered"));
    f.close();
  }
  Hdf5File r = Hdf5File::openReadOnly(path);
  EXPECT_EQ(r.readDatasetDouble("/a/values"), values);
  EXPECT_EQ(r.readAttributeString("/a", "label"), "buffered");
}

TEST_F(Hdf5FileTest, SlabbedWritesStoreTheSameValuesAndTheHookCanAbandonThem) {
  // 1.2 M rows of 3 doubles (29 MB): several slabs of about 4 MiB, the hook before each.
  const std::size_t rows = 1'200'000;
  std::vector<double> xyz(3 * rows);
  for (std::size_t k = 0; k < xyz.size(); ++k) xyz[k] = std::sin(0.001 * static_cast<double>(k));
  const std::string path = file("slabs.h5");
  int calls = 0;
  {
    Hdf5File f = Hdf5File::create(path);
    f.setBetweenParts([&] { ++calls; });
    f.writeDataset("/position", xyz, {rows, 3}, "m");
    f.setBetweenParts({});
    f.writeDataset("/whole", xyz, {rows, 3}, "m");
  }
  EXPECT_GE(calls, 6);  // 28.8 MB in slabs of about 4 MiB
  {
    Hdf5File r = Hdf5File::openReadOnly(path);
    EXPECT_EQ(r.readDatasetDouble("/position"), xyz);
    EXPECT_EQ(r.readDatasetDouble("/position"), r.readDatasetDouble("/whole"));
    EXPECT_EQ(r.datasetDims("/position"), (std::vector<std::size_t>{rows, 3}));
  }
  // A hook that throws abandons the write at once; the file stays usable.
  struct Stop {};
  int before = 0;
  {
    Hdf5File f = Hdf5File::openReadWrite(path);
    f.setBetweenParts([&] {
      if (++before == 3) throw Stop{};
    });
    EXPECT_THROW(f.writeDataset("/stopped", xyz, {rows, 3}, "m"), Stop);
    f.setBetweenParts({});
    f.setAttribute("/", "after", std::int64_t{1});
  }
  EXPECT_EQ(before, 3);
  EXPECT_EQ(Hdf5File::openReadOnly(path).readAttributeInt("/", "after"), 1);
}
