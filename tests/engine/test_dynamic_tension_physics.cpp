// Physics of the dynamic-tension scenario on the small example (1 um square, about 1,600 elements):
// the findings of the seed's Figures 2 and 3 (Longchamp et al., CSMA 2024, section 4).
//
// Sizes that matter here: L0 ≈ 0.98 um, bar wave speed C0 ≈ 5.6 km/s (measured by the preliminary
// run), so one wave transit takes L0 / C0 ≈ 0.18 ns and eq. 6 gives a V0 ramp of 1.1 ns; peak
// stresses are 50–70 MPa, so eq. 7 limits V0 runs in equilibrium to about 6e5 /s.
#include <algorithm>
#include <cmath>

#include "io/hdf5_file.hpp"
#include "test_dynamic_tension_support.hpp"

namespace rupture::test {
namespace {

double relativeSpread(std::initializer_list<double> values) {
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  return (*hi - *lo) / *lo;
}

// Figure 2: with the linear (VL) and heterogeneous (VH) initial fields, the two boundary stresses
// stay together at 1e7 /s, up to the peak (on the small example's sample; over sample seeds see
// EquilibriumOverSampleSeeds below).
TEST(DynamicTensionPhysics, VlAndVhStayInEquilibriumAt1e7) {
  for (const char* field : {"VL", "VH"}) {
    const nlohmann::json s = runSmall(1e7, field);
    SCOPED_TRACE(field);
    EXPECT_EQ(s["separated"], 1);
    EXPECT_LT(s["equilibrium_ratio"].get<double>(), 0.15);
    EXPECT_GT(s["broken_bond_fraction"].get<double>(), 0.0);
    // The face starts at V_max: the imposed rate is the requested one from the first step.
    EXPECT_DOUBLE_EQ(s["strain_rate_at_onset"].get<double>(), 1e7);
  }
}

// Figure 2a: from rest (V0) at 4e6 /s, X_max reaches its peak while X_min has hardly been loaded.
// Loading a sample from rest at 4e6 /s means a ramp much shorter than a wave transit (here 50 ps
// against 0.18 ns): the sample breaks next to X_max before the wave reaches X_min. Eq. 6's ramp
// (1.1 ns) would keep the faces together, but then the run breaks during the ramp, at a fraction
// of the requested rate (checked below): that conflict is eq. 7, 4e6 /s being above the rate a V0
// run can reach in equilibrium.
TEST(DynamicTensionPhysics, V0IsOutOfEquilibriumAt4e6) {
  const nlohmann::json fast = runSmall(4e6, "V0", {{"ramp_time", 5e-11}});
  EXPECT_GT(fast["equilibrium_ratio"].get<double>(), 0.3);
  EXPECT_GT(fast["max_stress_xmax"].get<double>(), 2.0 * fast["stress_xmin_at_peak"].get<double>());

  // With eq. 6's ramp the face stresses differ by ρ L0 a / 2 all along the loading branch.
  const nlohmann::json eq6 = runSmall(4e6, "V0");
  EXPECT_GT(eq6["equilibrium_ratio"].get<double>(), 0.3);
  const double ramp = eq6["ramp_time"].get<double>();
  const double expected = 3.0 * 2.0 * eq6["gauge_length"].get<double>() / eq6["wave_speed"].get<double>();
  EXPECT_NEAR(ramp, expected, 1e-9 * expected);                         // eq. 6, n = 3
  EXPECT_GT(ramp, 0.8e-9);
  EXPECT_LT(eq6["crack_onset_time"].get<double>(), ramp);               // broke during the ramp
  EXPECT_LT(eq6["strain_rate_at_onset"].get<double>(), 0.9 * 4e6);      // rate not reached
}

// Figure 3: below the eq. 7 limit the initial field does not matter.
// Only the loading branch matters here: the runs stop once σ̄ is back to half its peak.
const nlohmann::json kStopPastThePeak = {{"stop_fraction", 0.5}};

TEST(DynamicTensionPhysics, LowRateFieldsGiveTheSamePeak) {
  const nlohmann::json v0 = runSmall(1e5, "V0", {}, kStopPastThePeak);
  const nlohmann::json vl = runSmall(1e5, "VL", {}, kStopPastThePeak);
  const nlohmann::json vh = runSmall(1e5, "VH", {}, kStopPastThePeak);
  const double a = v0["peak_stress"].get<double>(), b = vl["peak_stress"].get<double>(),
               c = vh["peak_stress"].get<double>();
  EXPECT_LT(relativeSpread({a, b, c}), 0.05) << "V0 " << a << " VL " << b << " VH " << c;
  for (const auto* s : {&v0, &vl, &vh}) {
    EXPECT_LT((*s)["equilibrium_ratio"].get<double>(), 0.05);
    EXPECT_EQ((*s)["stop_reason"], "post_peak_drop");
  }
}

// Section 4, "Fissuration": cracking starts at the same strain whatever the rate, provided the
// sample is in equilibrium (VH at every rate; V0 below the eq. 7 limit), since the bonds have no
// rate dependence.
TEST(DynamicTensionPhysics, CrackOnsetDoesNotDependOnStrainRateInEquilibrium) {
  const double vh5 = runSmall(1e5, "VH", {}, kStopPastThePeak)["crack_onset_strain"].get<double>();
  const double vh6 = runSmall(1e6, "VH", {}, kStopPastThePeak)["crack_onset_strain"].get<double>();
  const double vh7 = runSmall(1e7, "VH", {}, kStopPastThePeak)["crack_onset_strain"].get<double>();
  const double v05 = runSmall(1e5, "V0", {}, kStopPastThePeak)["crack_onset_strain"].get<double>();
  EXPECT_LT(relativeSpread({vh5, vh6, vh7, v05}), 0.10)
      << "VH 1e5 " << vh5 << ", 1e6 " << vh6 << ", 1e7 " << vh7 << "; V0 1e5 " << v05;
}

// Figure 3 trend: strength rises with the rate in equilibrium, more with VL (stiffer apparent
// modulus: a linear field ignores the pores and the Poisson contraction); more bonds break.
TEST(DynamicTensionPhysics, PeakStressAndDamageRiseWithRate) {
  const nlohmann::json low = runSmall(1e5, "VH");
  const nlohmann::json high = runSmall(1e7, "VH");
  const nlohmann::json highLinear = runSmall(1e7, "VL");
  EXPECT_GT(high["peak_stress"].get<double>(), 1.15 * low["peak_stress"].get<double>());
  EXPECT_GT(highLinear["peak_stress"].get<double>(), high["peak_stress"].get<double>());
  EXPECT_GT(high["broken_bond_fraction"].get<double>(), 2.0 * low["broken_bond_fraction"].get<double>());
}

// The equilibrium ratio over [lo, hi] of strain, from the /series rows of a result file.
double seriesEquilibriumRatio(const fs::path& file, double lo, double hi) {
  const io::Hdf5File f = io::Hdf5File::openReadOnly(file.string());
  const auto strain = f.readDatasetDouble("/series/strain"), xmin = f.readDatasetDouble("/series/stress_xmin"),
             xmax = f.readDatasetDouble("/series/stress_xmax"), mean = f.readDatasetDouble("/series/stress_mean");
  double difference = 0, sum = 0;
  for (std::size_t k = 0; k < strain.size(); ++k)
    if (strain[k] >= lo && strain[k] <= hi) {
      difference += std::abs(xmax[k] - xmin[k]);
      sum += mean[k];
    }
  return difference / sum;
}

// Equilibrium at 1e7 /s over the sample seeds 1–6 of the small example (the seed's Fig. 2b, c). What
// holds on every sample: VH starts in equilibrium (the ratio from half the onset strain to the
// onset below the 0.15; 0.005–0.046 measured: the preliminary run's field is quasi-static,
// its small residual misfit scaled up with V_max), and closer to it than VL,
// whose linear field ignores the pores and the Poisson contraction and rings with an amplitude
// ∝ ρ C0 ε̇ L0 (7–35 % here). What does not: between the onset and the peak (about 30 ps, a sixth
// of a wave transit) a face feels only the cracks near it, so a pore next to a loaded face makes
// the loading-branch ratio of VH reach 0.16 (seed 1) and 0.38 (seed 2), 0.02–0.09 elsewhere
// (docs/dynamic-tension.md, "Equilibrium during fracture").
class EquilibriumOverSampleSeeds : public ::testing::TestWithParam<int> {};

TEST_P(EquilibriumOverSampleSeeds, VhStartsInEquilibriumAndCloserThanVl) {
  ScratchDir dir;
  double elastic[2];
  const char* fields[2] = {"VH", "VL"};
  for (int k = 0; k < 2; ++k) {
    nlohmann::json spec = smallSpec(1e7, fields[k]);
    spec["sample"]["seed"] = GetParam();
    const fs::path file = dir / (std::string(fields[k]) + ".h5");
    const nlohmann::json s = runToFile(spec, file);
    const double onset = s["crack_onset_strain"].get<double>();
    elastic[k] = seriesEquilibriumRatio(file, 0.5 * onset, onset);
    EXPECT_EQ(s["separated"], 1) << fields[k];
    EXPECT_GT(s["equilibrium_ratio"].get<double>(), 0.0) << fields[k];
  }
  EXPECT_LT(elastic[0], 0.15);
  EXPECT_LT(elastic[0], elastic[1]);
}

INSTANTIATE_TEST_SUITE_P(SmallExample, EquilibriumOverSampleSeeds, ::testing::Range(1, 7));

// The seed's move from single to multiple fragmentation (section 4, Fig. 4): at 1e5 /s one crack
// separates the sample and relaxes the stress before other pores crack (occultation); at 1e7 /s
// many pores crack before the relaxation waves reach them. Macroscopic fragments (≥ 1 % of the
// elements) at the end, VH, on sample seeds 1–3 of the small example.
class FragmentationOverSampleSeeds : public ::testing::TestWithParam<int> {};

TEST_P(FragmentationOverSampleSeeds, FewerFragmentsAtLowRate) {
  ScratchDir dir;
  nlohmann::json low = smallSpec(1e5, "VH"), high = smallSpec(1e7, "VH");
  low["sample"]["seed"] = high["sample"]["seed"] = GetParam();
  const nlohmann::json a = runToFile(low, dir / "low.h5"), b = runToFile(high, dir / "high.h5");
  // At 1e5 /s the run ends separated, or unloaded with a bending flap still joining the faces
  // (sample seed 1); at 1e7 /s the faces separate long before the strain limit.
  EXPECT_NE(a["stop_reason"], "max_strain");
  EXPECT_EQ(b["separated"], 1);
  EXPECT_LT(a["fragments"].get<int>(), b["fragments"].get<int>());
  EXPECT_LE(a["cracks_crossing"].get<int>(), b["cracks_crossing"].get<int>());
}

INSTANTIATE_TEST_SUITE_P(SmallExample, FragmentationOverSampleSeeds, ::testing::Range(1, 4));

}  // namespace
}  // namespace rupture::test
