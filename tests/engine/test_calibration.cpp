// Calibration: a fit for a target E and ν, re-measured, lands within 5 %; E scales linearly with E_μ.
#include <gtest/gtest.h>

#include <cmath>

#include "calibration/calibration.hpp"

using namespace rupture;

namespace {

struct Small {
  SampleSpec spec;
  MaterialSpec material;
  BondedSystem sample;
  Small() {
    spec.dimension = 2;
    spec.size = {0.2e-6, 0.2e-6, 0};
    spec.elementRadius = 3.3e-9;
    material.density = 6060;
    material.beam = {2865e9, 0.3, 0.3, 4e9};
    material.contact.youngModulus = 2865e9;
    buildSample(spec, material, sample);
  }
};

TEST(Calibration, MacroscopicModulusIsLinearInBeamModulus) {
  Small s;
  const ElasticProperties a = measureElasticProperties(s.sample, s.spec);
  BondedSystem stiffer = s.sample;
  stiffer.beam.youngModulus *= 2;
  const ElasticProperties b = measureElasticProperties(stiffer, s.spec);
  ASSERT_TRUE(a.converged);
  EXPECT_GT(a.youngModulus, 0);
  EXPECT_NEAR(b.youngModulus / a.youngModulus, 2.0, 0.01);
  EXPECT_NEAR(b.poissonRatio, a.poissonRatio, 0.005);
  EXPECT_GT(a.poissonRatio, 0.0);
  EXPECT_LT(a.poissonRatio, 1.0);
}

TEST(Calibration, RoundTripReachesTargetWithinFivePercent) {
  Small s;
  const double targetE = 150e9, targetNu = 0.4;
  const BeamFit fit = fitBeamParameters(s.sample, s.spec, targetE, targetNu);
  EXPECT_NEAR(fit.achieved.youngModulus, targetE, 0.05 * targetE);
  EXPECT_NEAR(fit.achieved.poissonRatio, targetNu, 0.05 * targetNu);
  EXPECT_GT(fit.beam.radiusRatio, 0.02);
  EXPECT_LE(fit.beam.radiusRatio, 1.0);
  // Re-measure independently with the fitted beams.
  BondedSystem check = s.sample;
  check.beam = fit.beam;
  const ElasticProperties again = measureElasticProperties(check, s.spec);
  EXPECT_NEAR(again.youngModulus, targetE, 0.05 * targetE);
  EXPECT_NEAR(again.poissonRatio, targetNu, 0.05 * targetNu);
}

TEST(Calibration, UnreachablePoissonRatioIsReportedNotGuessed) {
  Small s;
  EXPECT_THROW(fitBeamParameters(s.sample, s.spec, 150e9, -0.5), CalibrationError);
}

}  // namespace
