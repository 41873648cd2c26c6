// The result file of a dynamic-tension run, read back with the HDF5 C API: every group, dataset and
// attribute of the documented layout; the XDMF sidecar's references; the preliminary-run cache;
// cancellation (a valid file marked incomplete); the guards and the capture-strain check.
#include <hdf5.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <numbers>
#include <regex>
#include <thread>

#include "io/hdf5_file.hpp"
#include "io/xdmf_writer.hpp"
#include "test_dynamic_tension_support.hpp"

namespace rupture::test {
namespace {

/// Read-only access through the plain C API (not the engine's wrapper).
class CFile {
public:
  explicit CFile(const fs::path& path) : m_id(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)) {}
  ~CFile() {
    if (m_id >= 0) H5Fclose(m_id);
  }
  bool valid() const { return m_id >= 0; }
  bool exists(const std::string& path) const {
    // Check every level, as H5Lexists requires.
    std::size_t pos = 0;
    while ((pos = path.find('/', pos + 1)) != std::string::npos)
      if (H5Lexists(m_id, path.substr(0, pos).c_str(), H5P_DEFAULT) <= 0) return false;
    return H5Lexists(m_id, path.c_str(), H5P_DEFAULT) > 0;
  }
  bool hasAttribute(const std::string& object, const std::string& name) const {
    return H5Aexists_by_name(m_id, object.c_str(), name.c_str(), H5P_DEFAULT) > 0;
  }
  double attributeDouble(const std::string& object, const std::string& name) const {
    double v = std::nan("");
    hid_t a = H5Aopen_by_name(m_id, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
    if (a < 0) return v;
    H5Aread(a, H5T_NATIVE_DOUBLE, &v);
    H5Aclose(a);
    return v;
  }
  std::string attributeString(const std::string& object, const std::string& name) const {
    hid_t a = H5Aopen_by_name(m_id, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
    if (a < 0) return "(missing)";
    hid_t type = H5Aget_type(a);
    std::string out;
    if (H5Tget_class(type) == H5T_STRING && H5Tis_variable_str(type) > 0) {
      char* text = nullptr;
      hid_t mem = H5Tcopy(H5T_C_S1);
      H5Tset_size(mem, H5T_VARIABLE);
      H5Tset_cset(mem, H5T_CSET_UTF8);
      if (H5Aread(a, mem, &text) >= 0 && text) out = text;
      if (text) H5free_memory(text);
      H5Tclose(mem);
    } else {
      out = "(not a variable-length string)";
    }
    H5Tclose(type);
    H5Aclose(a);
    return out;
  }
  std::vector<hsize_t> dims(const std::string& path) const {
    hid_t d = H5Dopen2(m_id, path.c_str(), H5P_DEFAULT);
    if (d < 0) return {};
    hid_t space = H5Dget_space(d);
    const int rank = H5Sget_simple_extent_ndims(space);
    std::vector<hsize_t> out(static_cast<std::size_t>(std::max(rank, 0)));
    H5Sget_simple_extent_dims(space, out.data(), nullptr);
    H5Sclose(space);
    H5Dclose(d);
    return out;
  }
  bool chunkedAndCompressed(const std::string& path) const {
    hid_t d = H5Dopen2(m_id, path.c_str(), H5P_DEFAULT);
    hid_t plist = H5Dget_create_plist(d);
    const bool chunked = H5Pget_layout(plist) == H5D_CHUNKED;
    bool deflate = false;
    for (int k = 0; k < H5Pget_nfilters(plist); ++k) {
      unsigned flags = 0;
      size_t n = 0;
      deflate = deflate || H5Pget_filter2(plist, static_cast<unsigned>(k), &flags, &n, nullptr, 0, nullptr, nullptr) ==
                               H5Z_FILTER_DEFLATE;
    }
    H5Pclose(plist);
    H5Dclose(d);
    return chunked && deflate;
  }

private:
  hid_t m_id;
};

const char* const kSeries[] = {"time", "strain", "stress_xmin", "stress_xmax", "stress_mean",
                               "broken_bond_fraction", "kinetic_energy", "elastic_energy"};
const char* const kSummary[] = {"peak_stress", "strain_at_peak", "crack_onset_strain", "broken_bond_fraction",
                                "fragments", "equilibrium_ratio", "steps", "wall_time_s", "completed",
                                "elements", "bonds", "mean_coordination", "porosity", "time_step",
                                "equilibrium_ratio_at_peak", "debris", "largest_fragment_fraction",
                                "cracks_crossing", "separated", "separation_strain", "separation_time"};

TEST(DynamicTensionOutput, FileHasTheDocumentedLayout) {
  ScratchDir dir;
  nlohmann::json spec = smallSpec(1e7, "VH");
  spec["run"]["snapshot_strains"] = {0.0, 2e-4, 4e-4};
  const fs::path file = dir / "run.h5";
  const nlohmann::json summary = runToFile(spec, file);
  EXPECT_FALSE(fs::exists(file.string() + ".part"));

  CFile f(file);
  ASSERT_TRUE(f.valid());
  // /spec: the resolved spec as JSON, which validates and keeps the input's values.
  ASSERT_TRUE(f.hasAttribute("/spec", "json"));
  const nlohmann::json resolved = nlohmann::json::parse(f.attributeString("/spec", "json"));
  EXPECT_NO_THROW(validateSpec(resolved));
  EXPECT_EQ(resolved["loading"]["strain_rate"], 1e7);
  EXPECT_EQ(resolved["run"]["time_step_safety"], 0.15);
  EXPECT_EQ(nlohmann::json::parse(f.attributeString("/spec", "input")), spec);
  EXPECT_EQ(f.attributeString("/", "scenario"), "dynamic-tension");
  EXPECT_EQ(f.attributeDouble("/", "completed"), 1.0);

  // /series: 1-D, equal lengths, units.
  const auto rows = f.dims("/series/time");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_GT(rows[0], 20u);
  for (const char* name : kSeries) {
    const std::string path = std::string("/series/") + name;
    SCOPED_TRACE(path);
    ASSERT_TRUE(f.exists(path));
    EXPECT_EQ(f.dims(path), rows);
    EXPECT_TRUE(f.chunkedAndCompressed(path));
    EXPECT_TRUE(f.hasAttribute(path, "unit"));
  }
  EXPECT_EQ(f.attributeString("/series/stress_mean", "unit"), "Pa");
  EXPECT_EQ(f.attributeString("/series/time", "unit"), "s");
  EXPECT_EQ(f.attributeString("/series/kinetic_energy", "unit"), "J");

  // /summary: the scalars, each with a unit, equal to the returned summary.
  for (const char* name : kSummary) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(f.hasAttribute("/summary", name));
    EXPECT_TRUE(f.hasAttribute("/summary", std::string(name) + "_unit"));
    if (summary[name].is_number()) {
      EXPECT_DOUBLE_EQ(f.attributeDouble("/summary", name), summary[name].get<double>());
    }
  }
  EXPECT_EQ(f.attributeString("/summary", "peak_stress_unit"), "Pa");
  EXPECT_EQ(f.attributeString("/summary", "wall_time_s_unit"), "s");
  // At 1e7 /s the faces separate and cracks keep running until the example's strain limit.
  EXPECT_EQ(f.attributeString("/summary", "stop_reason"), "max_strain");
  EXPECT_EQ(summary["separated"], 1);
  EXPECT_GT(summary["separation_strain"].get<double>(), summary["strain_at_peak"].get<double>());
  EXPECT_GT(summary["peak_stress"].get<double>(), 1e7);
  EXPECT_GE(summary["fragments"].get<std::int64_t>(), 2);

  // /fragments: sizes (largest first, as many as the summary's fragments) and the element map.
  const auto k = static_cast<hsize_t>(summary["fragments"].get<std::int64_t>());
  EXPECT_EQ(f.dims("/fragments/sizes"), (std::vector<hsize_t>{k}));
  EXPECT_EQ(f.attributeDouble("/fragments", "count"), static_cast<double>(k));
  EXPECT_EQ(f.attributeDouble("/fragments", "debris"), summary["debris"].get<double>());
  EXPECT_EQ(f.attributeDouble("/fragments", "cracks_crossing"), summary["cracks_crossing"].get<double>());

  // /sample and /preliminary.
  const auto n = static_cast<hsize_t>(summary["elements"].get<std::int64_t>());
  const auto m = static_cast<hsize_t>(summary["bonds"].get<std::int64_t>());
  EXPECT_EQ(f.dims("/sample/bonds"), (std::vector<hsize_t>{m, 2}));
  EXPECT_EQ(f.dims("/sample/radius"), (std::vector<hsize_t>{n}));
  EXPECT_EQ(f.dims("/sample/face_group"), (std::vector<hsize_t>{n}));
  EXPECT_EQ(f.dims("/fragments/element_fragment"), (std::vector<hsize_t>{n}));
  EXPECT_EQ(f.attributeDouble("/preliminary", "used"), 1.0);
  for (const char* name : {"strain_rate", "capture_strain", "capture_time", "steps", "modulus", "wave_speed"})
    EXPECT_TRUE(f.hasAttribute("/preliminary", name)) << name;
  EXPECT_LT(f.attributeDouble("/preliminary", "capture_strain"), f.attributeDouble("/preliminary", "onset_strain"));

  // /snapshots: the three requested strains and the final state.
  for (const char* k : {"000000", "000001", "000002", "000003"}) {
    const std::string base = std::string("/snapshots/") + k;
    SCOPED_TRACE(base);
    ASSERT_TRUE(f.exists(base));
    EXPECT_EQ(f.dims(base + "/position"), (std::vector<hsize_t>{n, 3}));
    EXPECT_EQ(f.dims(base + "/velocity"), (std::vector<hsize_t>{n, 3}));
    EXPECT_EQ(f.dims(base + "/stress"), (std::vector<hsize_t>{n, 3, 3}));
    EXPECT_EQ(f.dims(base + "/damage"), (std::vector<hsize_t>{n}));
    EXPECT_EQ(f.dims(base + "/radius"), (std::vector<hsize_t>{n}));
    EXPECT_EQ(f.dims(base + "/bond_intact"), (std::vector<hsize_t>{m}));
    EXPECT_TRUE(f.hasAttribute(base, "time"));
    EXPECT_TRUE(f.hasAttribute(base, "strain"));
  }
  EXPECT_FALSE(f.exists("/snapshots/000004"));
  EXPECT_GE(f.attributeDouble("/snapshots/000001", "strain"), 2e-4);
  EXPECT_EQ(f.attributeString("/snapshots/000003", "trigger"), "final");
}

// In a quasi-static state the volume average of the per-element virial stress equals the boundary
// stress: (1/V) Σ Ω_i σ_i = σ̄ (virial theorem; Ω_i = V_i / φ).
TEST(DynamicTensionOutput, VirialStressAveragesToTheBoundaryStress) {
  ScratchDir dir;
  nlohmann::json spec = smallSpec(1e5, "VH");
  spec["run"]["snapshot_strains"] = {1.5e-4};
  const fs::path file = dir / "run.h5";
  runToFile(spec, file);
  io::Hdf5File f = io::Hdf5File::openReadOnly(file.string());
  const auto stress = f.readDatasetDouble("/snapshots/000000/stress");
  const auto radius = f.readDatasetDouble("/snapshots/000000/radius");
  const double phi = f.readAttributeDouble("/sample", "packing_fraction");
  const double t = f.readAttributeDouble("/sample", "thickness");
  const double strain = f.readAttributeDouble("/snapshots/000000", "strain");
  double sum = 0;
  for (std::size_t k = 0; k < radius.size(); ++k)
    sum += stress[9 * k] * std::numbers::pi * radius[k] * radius[k] * t / phi;
  const double volume = 1e-6 * 1e-6 * t;
  const auto strains = f.readDatasetDouble("/series/strain");
  const auto mean = f.readDatasetDouble("/series/stress_mean");
  std::size_t row = 0;
  while (row + 1 < strains.size() && strains[row] < strain) ++row;
  EXPECT_NEAR(sum / volume, mean[row], 0.05 * mean[row]);
  // Tension: the bulk of the elements carries a positive σ_xx.
  std::size_t positive = 0;
  for (std::size_t k = 0; k < radius.size(); ++k) positive += stress[9 * k] > 0;
  EXPECT_GT(positive, radius.size() * 3 / 4);
}

TEST(DynamicTensionOutput, XdmfSidecarReferencesExistingDatasets) {
  ScratchDir dir;
  nlohmann::json spec = smallSpec(1e7, "VL");
  spec["run"]["snapshot_strains"] = {0.0, 3e-4};
  const fs::path file = dir / "run.h5";
  runToFile(spec, file);
  const fs::path sidecar = dir / "run.xdmf2";
  io::writeXdmfSidecar(file.string(), sidecar.string());
  const std::string xml = readText(sidecar);
  const std::regex ref(R"(>\s*([^<>:\s]+\.h5):(/[^<\s]+)\s*<)");
  CFile f(file);
  std::size_t count = 0;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), ref); it != std::sregex_iterator(); ++it) {
    EXPECT_EQ((*it)[1].str(), "run.h5");
    EXPECT_TRUE(f.exists((*it)[2].str())) << (*it)[2].str();
    ++count;
  }
  // 3 snapshots × (position, velocity, stress, damage, radius) and × the bond grid (pairs,
  // positions, bond_intact, bond_load, bond_equivalent_stress).
  EXPECT_EQ(count, 3u * (5u + 5u));
}

TEST(DynamicTensionOutput, ConcurrentRunsOnOneSampleComputeThePreliminaryRunOnce) {
  // Two workers of a sweep start VH runs on the same new sample at once: one computes the
  // preliminary run while the other waits on the cache entry's lock, then reads it.
  useTestCache();
  ScratchDir dir;
  ::setenv("RUPTURE_CACHE_DIR", (dir / "cache").c_str(), 1);
  RunControl c1, c2;
  RunOutcome first, second;
  std::thread other([&] { second = runSpec(smallSpec(1e7, "VH"), (dir / "b.h5").string(), c2, 1); });
  first = runSpec(smallSpec(2e6, "VH"), (dir / "a.h5").string(), c1, 1);
  other.join();
  ::setenv("RUPTURE_CACHE_DIR", useTestCache().c_str(), 1);
  io::Hdf5File a = io::Hdf5File::openReadOnly((dir / "a.h5").string());
  io::Hdf5File b = io::Hdf5File::openReadOnly((dir / "b.h5").string());
  EXPECT_EQ(a.readAttributeInt("/preliminary", "from_cache") + b.readAttributeInt("/preliminary", "from_cache"), 1);
  EXPECT_EQ(a.readAttributeString("/preliminary", "cache_file"), b.readAttributeString("/preliminary", "cache_file"));
  EXPECT_EQ(first.summary["completed"], 1);
  EXPECT_EQ(second.summary["completed"], 1);
}

TEST(DynamicTensionOutput, PreliminaryRunIsCached) {
  useTestCache();
  ScratchDir dir;
  nlohmann::json spec = smallSpec(1e7, "VH");
  ::setenv("RUPTURE_CACHE_DIR", (dir / "cache").c_str(), 1);
  RunControl c1, c2;
  const RunOutcome first = runSpec(spec, (dir / "a.h5").string(), c1, 1);
  const RunOutcome second = runSpec(spec, (dir / "b.h5").string(), c2, 1);
  ::setenv("RUPTURE_CACHE_DIR", useTestCache().c_str(), 1);
  io::Hdf5File a = io::Hdf5File::openReadOnly((dir / "a.h5").string());
  io::Hdf5File b = io::Hdf5File::openReadOnly((dir / "b.h5").string());
  EXPECT_EQ(a.readAttributeInt("/preliminary", "from_cache"), 0);
  EXPECT_EQ(b.readAttributeInt("/preliminary", "from_cache"), 1);
  EXPECT_EQ(a.readAttributeString("/preliminary", "cache_file"), b.readAttributeString("/preliminary", "cache_file"));
  // A name inside the cache directory, never the machine's absolute path.
  const std::string cacheName = a.readAttributeString("/preliminary", "cache_file");
  EXPECT_EQ(cacheName.find('/'), std::string::npos) << cacheName;
  EXPECT_TRUE(fs::exists(dir / "cache" / cacheName));
  EXPECT_EQ(first.summary["peak_stress"], second.summary["peak_stress"]);  // bit-identical field
  EXPECT_EQ(first.summary["steps"], second.summary["steps"]);
  // The packed sample is cached too (scenarios/bonded/sample_cache.hpp), and gives the same run.
  EXPECT_EQ(first.summary["sample_from_cache"], 0);
  EXPECT_EQ(second.summary["sample_from_cache"], 1);
  EXPECT_EQ(first.summary["bonds"], second.summary["bonds"]);
  std::size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir / "cache")) entries += e.path().extension() == ".h5";
  EXPECT_EQ(entries, 2u);  // the preliminary run and the sample; no temporary left behind
}

TEST(DynamicTensionOutput, CancelledRunLeavesAValidIncompleteFile) {
  useTestCache();
  ScratchDir dir;
  // Cancelled before it starts: the sample build stops at once, and the file holds the spec and a
  // summary saying so, with empty series and no snapshot (there is no sample to show).
  {
    RunControl control;
    control.cancel = true;
    const RunOutcome out = runSpec(smallSpec(1e6, "VL"), (dir / "early.h5").string(), control, 1);
    EXPECT_FALSE(out.completed);
    EXPECT_EQ(out.summary["completed"], 0);
    EXPECT_EQ(out.summary["stop_reason"], "cancelled");
    io::Hdf5File f = io::Hdf5File::openReadOnly((dir / "early.h5").string());
    EXPECT_EQ(f.readAttributeInt("/summary", "completed"), 0);
    EXPECT_EQ(f.readAttributeInt("/", "completed"), 0);
    EXPECT_TRUE(f.hasAttribute("/spec", "json"));
    EXPECT_EQ(f.datasetDims("/series/stress_mean"), std::vector<std::size_t>{0});
    EXPECT_TRUE(f.listGroup("/snapshots").empty());
    EXPECT_FALSE(f.exists("/sample"));
  }
  // Cancelled from another thread in the middle of a run.
  {
    RunControl control;
    nlohmann::json spec = smallSpec(1e5, "V0");
    spec["loading"]["ramp_time"] = 1e-9;  // no preliminary run
    std::thread watcher([&] {
      while (control.progress.load() < 0.05) std::this_thread::sleep_for(std::chrono::milliseconds(5));
      control.cancel = true;
    });
    const auto start = std::chrono::steady_clock::now();
    const RunOutcome out = runSpec(spec, (dir / "late.h5").string(), control, 1);
    watcher.join();
    EXPECT_FALSE(out.completed);
    EXPECT_LT(control.progress.load(), 1.0);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
    io::Hdf5File f = io::Hdf5File::openReadOnly((dir / "late.h5").string());
    EXPECT_EQ(f.readAttributeInt("/summary", "completed"), 0);
    EXPECT_GT(f.datasetDims("/series/time")[0], 1u);
    EXPECT_NO_THROW(io::writeXdmfSidecar((dir / "late.h5").string(), (dir / "late.xdmf2").string()));
  }
  EXPECT_FALSE(fs::exists(dir / "late.h5.part"));
}

TEST(DynamicTensionOutput, StepGuardAndCaptureStrainCheck) {
  useTestCache();
  ScratchDir dir;
  nlohmann::json spec = smallSpec(1e6, "VL");
  spec["run"]["max_steps"] = 10;
  RunControl control;
  const RunOutcome out = runSpec(spec, (dir / "guard.h5").string(), control, 1);
  EXPECT_TRUE(out.completed);
  EXPECT_EQ(out.summary["stop_reason"], "max_steps");
  EXPECT_EQ(out.summary["steps"], 10);
  EXPECT_TRUE(out.summary["crack_onset_strain"].is_null());  // no bond broke: null in JSON, NaN in the file
  io::Hdf5File f = io::Hdf5File::openReadOnly((dir / "guard.h5").string());
  EXPECT_TRUE(std::isnan(f.readAttributeDouble("/summary", "crack_onset_strain")));

  // A capture strain past the first break of the preliminary run is a spec error naming the field,
  // and nothing is left behind.
  nlohmann::json late = smallSpec(1e6, "VH");
  late["loading"]["vh_capture_strain"] = 2e-3;
  RunControl c2;
  try {
    runSpec(late, (dir / "late.h5").string(), c2, 1);
    FAIL() << "accepted";
  } catch (const SpecError& e) {
    EXPECT_EQ(e.field(), "loading.vh_capture_strain");
  }
  EXPECT_FALSE(fs::exists(dir / "late.h5"));
  EXPECT_FALSE(fs::exists(dir / "late.h5.part"));
}

}  // namespace
}  // namespace rupture::test
