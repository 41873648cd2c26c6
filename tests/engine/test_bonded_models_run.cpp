// Every bonded model runs the dynamic-tension scenario end to end (the examples of each model):
// the mean stress rises to a peak, bonds break, and the run stops on the post-peak drop
// (run.stop_fraction), with the damage index in the snapshots.
#include <hdf5.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "support/test_support.hpp"
#include "test_dynamic_tension_support.hpp"

namespace rupture::test {
namespace {

class BondedModelRun : public ::testing::TestWithParam<std::string> {};

TEST_P(BondedModelRun, DynamicTensionReachesAPeakAndDrops) {
  nlohmann::json spec = readJson(examplePath("dynamic-tension-" + GetParam() + ".json"));
  spec["run"]["stop_fraction"] = 0.1;  // the optional post-peak stop (the default waits for separation)
  ASSERT_EQ(rupture::testing::rejectedField(spec), "");
  rupture::testing::ScratchDir dir;
  RunControl control;
  const RunOutcome out = runSpec(spec, (dir / "run.h5").string(), control, 1);
  ASSERT_TRUE(out.completed);
  EXPECT_EQ(out.summary["stop_reason"], "post_peak_drop") << out.summary.dump();
  EXPECT_GT(out.summary["peak_stress"].get<double>(), 0.0);
  EXPECT_GT(out.summary["broken_bonds"].get<double>(), 0.0);
  EXPECT_GT(out.summary["final_strain"].get<double>(), out.summary["strain_at_peak"].get<double>());
  // The final snapshot's damage index is in [0, 1] and somewhere positive.
  const hid_t file = H5Fopen((dir / "run.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t snapshots = H5Gopen2(file, "/snapshots", H5P_DEFAULT);
  H5G_info_t info;
  H5Gget_info(snapshots, &info);
  ASSERT_GT(info.nlinks, 0u);
  char name[16];
  std::snprintf(name, sizeof name, "%06d/damage", static_cast<int>(info.nlinks - 1));
  const hid_t set = H5Dopen2(snapshots, name, H5P_DEFAULT);
  ASSERT_GE(set, 0);
  const hid_t space = H5Dget_space(set);
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space, &n, nullptr);
  std::vector<double> damage(n);
  H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, damage.data());
  H5Sclose(space); H5Dclose(set); H5Gclose(snapshots); H5Fclose(file);
  EXPECT_EQ(n, static_cast<hsize_t>(out.summary["elements"].get<double>()));
  EXPECT_GT(*std::max_element(damage.begin(), damage.end()), 0.0);
  EXPECT_GE(*std::min_element(damage.begin(), damage.end()), 0.0);
  EXPECT_LE(*std::max_element(damage.begin(), damage.end()), 1.0);
}

INSTANTIATE_TEST_SUITE_P(EveryModel, BondedModelRun, ::testing::Values("hookean", "born", "pmb"));

}  // namespace
}  // namespace rupture::test
