// Dynamic tension in 3D (examples/dynamic-tension-3d.json: a 0.4 um cube of about 930 spheres with
// 11 % porosity), checked like the 2D small example: at a rate below eq. 7's limit the sample is
// in equilibrium whatever the initial field, the response is elastic up to the first broken bond,
// and the faces separate into fragments.
#include <cmath>

#include "io/hdf5_file.hpp"
#include "test_dynamic_tension_support.hpp"

namespace rupture::test {
namespace {

nlohmann::json example3d(double strainRate, const std::string& field) {
  nlohmann::json spec = readJson(examplePath("dynamic-tension-3d.json"));
  spec["loading"]["strain_rate"] = strainRate;
  spec["loading"]["initial_velocity"] = field;
  return spec;
}

/// σ̄ at strain `e`, linearly interpolated between the /series rows.
double meanStressAt(const fs::path& file, double e) {
  const io::Hdf5File f = io::Hdf5File::openReadOnly(file.string());
  const auto strain = f.readDatasetDouble("/series/strain"), mean = f.readDatasetDouble("/series/stress_mean");
  for (std::size_t k = 1; k < strain.size(); ++k)
    if (strain[k] >= e) {
      const double w = (e - strain[k - 1]) / (strain[k] - strain[k - 1]);
      return mean[k - 1] + w * (mean[k] - mean[k - 1]);
    }
  return std::nan("");
}

TEST(DynamicTension3d, LowRateEquilibriumOnsetAndPeak) {
  ScratchDir dir;
  const double rate = 1e6;
  const nlohmann::json vh = runToFile(example3d(rate, "VH"), dir / "vh.h5");
  const nlohmann::json v0 = runToFile(example3d(rate, "V0"), dir / "v0.h5");

  // 1e6 /s is below eq. 7's limit ε̇_max = σ_R / (n L0 √(E ρ)) = σ_R C0 / (n L0 E) for this sample,
  // and the V0 run's eq. 6 ramp is over before the first break.
  const double limit = vh["peak_stress"].get<double>() * vh["wave_speed"].get<double>() /
                       (3.0 * vh["gauge_length"].get<double>() * vh["modulus"].get<double>());
  EXPECT_GT(limit, rate);
  EXPECT_DOUBLE_EQ(v0["strain_rate_at_onset"].get<double>(), rate);

  for (const auto* s : {&vh, &v0}) {
    SCOPED_TRACE((*s)["initial_velocity"].get<std::string>());
    EXPECT_LT((*s)["equilibrium_ratio"].get<double>(), 0.15);  // both faces carry the same load
    EXPECT_GT((*s)["strain_at_peak"].get<double>(), (*s)["crack_onset_strain"].get<double>());
    EXPECT_EQ((*s)["separated"], 1);
    EXPECT_GE((*s)["fragments"].get<int>(), 2);
    EXPECT_GE((*s)["cracks_crossing"].get<int>(), 1);
  }
  // In equilibrium the initial field does not matter (seed's Fig. 3 below 1e6 /s).
  EXPECT_NEAR(v0["peak_stress"].get<double>(), vh["peak_stress"].get<double>(), 0.05 * vh["peak_stress"].get<double>());
  EXPECT_NEAR(v0["crack_onset_strain"].get<double>(), vh["crack_onset_strain"].get<double>(),
              0.10 * vh["crack_onset_strain"].get<double>());
  // Elastic up to the first break: σ̄ = E ε there, E the modulus measured by the preliminary run.
  const double onset = vh["crack_onset_strain"].get<double>();
  EXPECT_NEAR(meanStressAt(dir / "vh.h5", onset), vh["modulus"].get<double>() * onset,
              0.10 * vh["modulus"].get<double>() * onset);
}

}  // namespace
}  // namespace rupture::test
