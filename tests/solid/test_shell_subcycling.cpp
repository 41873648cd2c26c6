// Multi-rate stepping of the SPH shell (shell/step_classes.hpp): a plate refined about a thickness
// step, whose finest nodes set the single-rate step, against the single-rate scheme; the
// conservation laws through the class interfaces; bitwise the same on one and two threads. The
// spectral step estimate (shell/shell_spectrum.cpp): its frequency is the central difference's
// stability limit, and its longer steps give the bound's results.
#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "shell/sph_shell.hpp"

namespace rupture {
namespace {

constexpr double kSpotRadius = 0.04;   // the seed's Ø 80 mm spot face
constexpr double kThin = 2.0e-3, kThick = 8.0e-3;

/// A spot face of kThin in a bottom of kThick, clamped at r = 70 mm (the seed's Ø 140 mm), its rings refined to a
/// quarter of the spacing about the step (as the tank's plate is at the seed's inputs).
ShellNodes steppedRefinedPlate(bool clamped = true) {
  const double coarse = kSpotRadius / 9.5, fine = 0.25 * coarse, rim = coarse * std::round(0.07 / coarse);
  ShellNodes nodes = ringDiskNodes(refinedRingRadii(rim, coarse, fine, kSpotRadius, 3));
  nodes.thickness.resize(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i)
    nodes.thickness[i] = std::hypot(nodes.x[i], nodes.y[i]) < kSpotRadius ? kThin : kThick;
  if (!clamped) {
    std::fill(nodes.clamped.begin(), nodes.clamped.end(), std::uint8_t{0});
    nodes.integrationArea = nodes.kernelVolume;
  }
  return nodes;
}

using StepEstimate = ShellParameters::StepEstimate;

ShellParameters elasticPlate(bool subcycling, StepEstimate estimate = StepEstimate::Bound) {
  ShellParameters p;
  p.thickness = kThin;
  p.plasticity = false;
  p.subcycling = subcycling;
  p.stepEstimate = estimate;
  return p;
}

/// The interval the shell is advanced by, as a fluid step would: 32 single-rate steps (the seed's
/// tank test takes 32 shell steps per fluid step).
double interval(const SphShell& shell) { return 31.7 * shell.stableTimeStep(); }

struct PulseHistory {
  std::vector<double> centre;  ///< centre deflection after each interval (m)
  double work = 0.0;           ///< work of the external forces (J)
  double kinetic = 0.0, strain = 0.0;
  std::uint64_t evaluations = 0, expectedEvaluations = 0;
  std::size_t nodes = 0;
  long fineSteps = 0;
  int coarsest = 0;  ///< the coarsest class of the last interval (0: it ran single-rate)
};

/// A half-sine pressure pulse of amplitude p over the spot face (r < kSpotRadius), dead loads held
/// constant over each interval (as the fluid's impulses are), then free vibration.
PulseHistory pressurePulse(bool subcycling, double duration, double total, StepEstimate estimate = StepEstimate::Bound) {
  const ShellNodes nodes = steppedRefinedPlate();
  SphShell shell(nodes, elasticPlate(subcycling, estimate));
  // The same intervals whatever the estimate: the bound's 32 single-rate steps.
  const double dt = interval(SphShell(nodes, elasticPlate(false))), pressure = 2.0e5;
  PulseHistory out;
  out.nodes = shell.size();
  const int intervals = static_cast<int>(total / dt);
  for (int k = 0; k < intervals; ++k) {
    const double t = (k + 0.5) * dt;
    const double p = t < duration ? pressure * std::sin(std::numbers::pi * t / duration) : 0.0;
    std::vector<std::array<double, 3>> force(shell.size(), {0.0, 0.0, 0.0});
    for (std::size_t i = 0; i < shell.size(); ++i)
      if (!shell.clamped(i) && std::hypot(nodes.x[i], nodes.y[i]) < kSpotRadius) force[i][2] = -p * shell.integrationArea(i);
    std::vector<std::array<double, 3>> before = shell.positions();
    for (std::size_t i = 0; i < shell.size(); ++i) shell.setExternalForce(i, force[i]);
    const long fine = shell.advanceInterval(dt);
    out.fineSteps += fine;
    const ShellStepClasses& classes = shell.stepClasses();
    out.coarsest = classes.coarsest;
    for (int c = 0; c <= classes.coarsest; ++c)
      out.expectedEvaluations += (classes.pointsUpTo[c] - (c > 0 ? classes.pointsUpTo[c - 1] : 0)) * static_cast<std::uint64_t>(fine >> c);
    // A force constant over the interval does the work F·Δx exactly.
    for (std::size_t i = 0; i < shell.size(); ++i)
      for (int a = 0; a < 3; ++a) out.work += force[i][a] * (shell.positions()[i][a] - before[i][a]);
    out.centre.push_back(shell.deflection(0));
  }
  // The energies at the end: the strain energy of x_{n+1} and the kinetic energy at the same time,
  // the mean of the leapfrog's staggered velocities v_{n+1/2} and v_{n+3/2} (one more fine step,
  // free of load: the pulse is over), whose error is second order in the step, not first.
  out.evaluations = shell.pointEvaluations();
  out.strain = shell.strainEnergy();
  const double kineticBefore = shell.kineticEnergy();
  shell.step(dt / static_cast<double>(out.fineSteps / intervals));
  out.kinetic = 0.5 * (kineticBefore + shell.kineticEnergy());
  return out;
}

TEST(ShellSubcycling, ClassesFollowTheStepAndTheSpacing) {
  const ShellNodes nodes = steppedRefinedPlate();
  SphShell shell(nodes, elasticPlate(true));
  const double single = shell.stableTimeStep();
  double finest = 1.0, coarsest = 0.0;
  for (std::size_t i = 0; i < shell.size(); ++i) {
    if (shell.clamped(i)) continue;
    EXPECT_GE(shell.pointStableStep(i), single);
    EXPECT_GE(shell.nodeStableStep(i), single);
    finest = std::min(finest, shell.nodeStableStep(i)), coarsest = std::max(coarsest, shell.pointStableStep(i));
  }
  // The single-rate step is the thin nodes' beside the step: their translation against the
  // bottom's stress points (√(t_j / t_i) = 2) and the quarter spacing.
  EXPECT_NEAR(finest / single, 1.0, 1e-12);
  EXPECT_GT(coarsest / single, 6.0) << "the coarse plate's points: spacing 4 times, no step";
  shell.advanceInterval(interval(shell));
  const ShellStepClasses& classes = shell.stepClasses();
  EXPECT_GE(classes.coarsest, 2);
  // Points in the bottom whose kernels reach thin nodes are the finest; the coarse spot face's
  // centre is coarse.
  int finestBottom = 99;
  for (std::size_t i = 0; i < shell.size(); ++i) {
    const double r = std::hypot(nodes.x[i], nodes.y[i]);
    if (r > kSpotRadius && r < kSpotRadius + 0.5 * nodes.nodeSpacing[i]) finestBottom = std::min<int>(finestBottom, classes.point[i]);
  }
  EXPECT_EQ(finestBottom, 0);
  EXPECT_EQ(classes.point[0], classes.coarsest) << "the centre node";
  EXPECT_LT(classes.pointsUpTo[0], shell.size() / 2) << "most points are coarser than the finest class";
}

TEST(ShellSubcycling, SingleRateIntervalIsTheLoopOfSteps) {
  const ShellNodes nodes = steppedRefinedPlate();
  SphShell a(nodes, elasticPlate(false)), b(nodes, elasticPlate(false));
  a.setPressure(1.0e5), b.setPressure(1.0e5);
  const double dt = interval(a);
  const long steps = a.advanceInterval(dt);
  EXPECT_EQ(steps, 32);
  for (long k = 0; k < steps; ++k) b.step(dt / static_cast<double>(steps));
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(a.positions()[i][c], b.positions()[i][c]) << "node " << i;
}

TEST(ShellSubcycling, PressurePulseFollowsTheSingleRateAndKeepsTheEnergy) {
  // A quarter of the plate's first period of loading, then as much again of free vibration.
  const double duration = 0.075e-3, total = 0.15e-3;
  const PulseHistory single = pressurePulse(false, duration, total), multi = pressurePulse(true, duration, total);
  ASSERT_EQ(single.centre.size(), multi.centre.size());
  double largest = 0.0, difference = 0.0;
  for (std::size_t k = 0; k < single.centre.size(); ++k) {
    largest = std::max(largest, std::fabs(single.centre[k]));
    difference = std::max(difference, std::fabs(multi.centre[k] - single.centre[k]));
  }
  EXPECT_GT(largest, 1e-5) << "the pulse bends the plate";
  EXPECT_LT(difference / largest, 0.01) << "the centre's deflection history, against the single rate";
  for (const PulseHistory* h : {&single, &multi}) {
    const double balance = h->kinetic + h->strain - h->work;
    EXPECT_LT(std::fabs(balance) / h->work, 0.005)
        << (h == &single ? "single" : "multi") << "-rate: kinetic " << h->kinetic << " J + strain " << h->strain
        << " J − external work " << h->work << " J";
  }
  // What it saves: each point is evaluated K / 2^c times an interval instead of K times.
  EXPECT_EQ(single.evaluations, static_cast<std::uint64_t>(single.fineSteps) * single.nodes);
  EXPECT_EQ(multi.evaluations, multi.expectedEvaluations);
  EXPECT_LT(multi.evaluations, single.evaluations);
}

TEST(ShellSubcycling, SpectralEstimateFollowsTheSingleRateAndKeepsTheEnergy) {
  // The same pulse with the steps from the measured spectrum (several times the bound's), single
  // rate and subcycled, against the bound's single rate.
  const double duration = 0.075e-3, total = 0.15e-3;
  const PulseHistory reference = pressurePulse(false, duration, total);
  for (bool subcycling : {false, true}) {
    const PulseHistory spectral = pressurePulse(subcycling, duration, total, StepEstimate::Spectral);
    ASSERT_EQ(reference.centre.size(), spectral.centre.size());
    double largest = 0.0, difference = 0.0;
    for (std::size_t k = 0; k < reference.centre.size(); ++k) {
      largest = std::max(largest, std::fabs(reference.centre[k]));
      difference = std::max(difference, std::fabs(spectral.centre[k] - reference.centre[k]));
    }
    EXPECT_LT(difference / largest, 0.01) << (subcycling ? "subcycled" : "single rate") << ": the centre's deflection history";
    const double balance = spectral.kinetic + spectral.strain - spectral.work;
    EXPECT_LT(std::fabs(balance) / spectral.work, 0.005) << (subcycling ? "subcycled" : "single rate") << ": energy balance";
    EXPECT_LT(2 * spectral.fineSteps, reference.fineSteps) << "the measured step is at least twice the bound's";
    // On this plate the groups' measured frequencies lie within 8 % of each other (5.22, 4.99 and
    // 4.85 × 10⁶ rad/s): the single rate's 7 fine steps an interval cost less than any multi-rate
    // plan at kMultiRateCourantFactor of the limit, and the planner takes it. The multi-rate plans
    // on measured steps: StepClasses.MultiRateStepSetsTheSubcycledPlansFineStep.
    EXPECT_EQ(spectral.coarsest, 0) << (subcycling ? "subcycled" : "single rate");
  }
}

TEST(StepClasses, MultiRateStepSetsTheSubcycledPlansFineStep) {
  // 100 stiff points (own step 1) and 900 soft ones (8) over an interval of 16: the single rate
  // takes 16 steps of 1 (16,000 evaluations); subcycled, 16 fine steps with the soft points at
  // class 3 (3,400).
  std::vector<double> steps(1000, 8.0);
  std::fill(steps.begin(), steps.begin() + 100, 1.0);
  const SubcyclingPlan bound = planSubcycling(steps, 1.0, 16.0);
  EXPECT_EQ(bound.fineSteps, 16);
  EXPECT_EQ(bound.coarsest, 3);
  // The same points at half their steps for the multi-rate scheme (the measured estimate's
  // kMultiRateCourantFactor), the single rate still at 1: the subcycled plans take K from the
  // finest multi-rate step, 32 fine steps of 0.5, and no class steps beyond its points' own.
  std::vector<double> half = steps;
  for (double& h : half) h *= 0.5;
  const SubcyclingPlan measured = planSubcycling(half, 1.0, 16.0, 0.5);
  EXPECT_EQ(measured.fineSteps, 32);
  EXPECT_DOUBLE_EQ(measured.fineStep, 0.5);
  EXPECT_EQ(measured.coarsest, 3);
  EXPECT_LE(std::ldexp(measured.fineStep, measured.coarsest), 4.0);
  // Where the soft points are barely softer, no subcycled plan at half the steps beats the
  // single rate at the full one: 16 steps, class 0.
  std::vector<double> close(1000, 0.5 * 1.1);
  const SubcyclingPlan single = planSubcycling(close, 1.0, 16.0, 0.5);
  EXPECT_EQ(single.fineSteps, 16);
  EXPECT_EQ(single.coarsest, 0);
}

/// Kinetic energy after `steps` single-rate steps of dt from small random velocities (every mode
/// excited), relative to the start's; the plate elastic, free of load.
double energyGrowth(const ShellNodes& nodes, double dt, int steps) {
  SphShell shell(nodes, elasticPlate(false));
  std::uint64_t state = 88172645463325252ULL;
  auto next = [&]() {  // xorshift: a fixed, portable sequence
    state ^= state << 13, state ^= state >> 7, state ^= state << 17;
    return static_cast<double>(state % 2000001) / 1.0e6 - 1.0;
  };
  for (std::size_t i = 0; i < shell.size(); ++i)
    if (!shell.clamped(i)) shell.setNodeState(i, shell.positions()[i], {0.0, 0.0, 1.0}, {1e-3 * next(), 1e-3 * next(), 1e-3 * next()});
  const double before = shell.kineticEnergy();
  for (int k = 0; k < steps; ++k) shell.step(dt);
  return shell.kineticEnergy() / before;
}

TEST(ShellSpectrum, MeasuredFrequencyIsTheCentralDifferencesStabilityLimit) {
  // ω_max dt ≤ 2: the central difference is stable just below 2/ω_max and blows up just above,
  // if ω_max is the operator's largest frequency. The bound is above it.
  const ShellNodes nodes = steppedRefinedPlate();
  SphShell shell(nodes, elasticPlate(false));
  const std::vector<std::uint8_t> all(shell.size(), 1);
  const double omega = shell.maxFrequency(all, all, 100);
  const double bound = 2.0 * ShellParameters{}.courantFactor / shell.stableTimeStep();
  EXPECT_LT(omega, bound) << "the bound bounds";
  EXPECT_GT(omega, 0.1 * bound);
  const double stable = energyGrowth(nodes, 0.97 * 2.0 / omega, 2000);
  const double unstable = energyGrowth(nodes, 1.05 * 2.0 / omega, 2000);
  EXPECT_LT(stable, 10.0) << "at 0.97 of 2/ω_max";
  EXPECT_TRUE(!std::isfinite(unstable) || unstable > 1e6) << "at 1.05 of 2/ω_max: " << unstable;
  // Fewer iterations fall short of the top of the spectrum, never above it.
  EXPECT_LE(shell.maxFrequency(all, all, 30), omega * (1.0 + 1e-9));
  EXPECT_GT(shell.maxFrequency(all, all, 30), 0.99 * omega);
}

TEST(ShellSpectrum, MeasuringLeavesTheStateAsItWas) {
  const ShellNodes nodes = steppedRefinedPlate();
  ShellParameters p = elasticPlate(true);
  p.plasticity = true;
  p.damage = true;
  SphShell a(nodes, p), b(nodes, p);
  a.setPressure(4.0e6), b.setPressure(4.0e6);
  const double dt = interval(a);
  for (int k = 0; k < 3; ++k) a.advanceInterval(dt), b.advanceInterval(dt);
  const std::vector<std::uint8_t> all(a.size(), 1);
  EXPECT_GT(a.maxFrequency(all, all, 10), 0.0);
  for (int k = 0; k < 3; ++k) a.advanceInterval(dt), b.advanceInterval(dt);
  EXPECT_EQ(a.pointEvaluations(), b.pointEvaluations());
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      ASSERT_EQ(a.positions()[i][c], b.positions()[i][c]) << "node " << i;
      ASSERT_EQ(a.normals()[i][c], b.normals()[i][c]) << "node " << i;
    }
}

TEST(ShellSpectrum, GroupsKeepTheBoundsOrderAndTheFinestSetsTheStep) {
  const ShellNodes nodes = steppedRefinedPlate();
  SphShell bound(nodes, elasticPlate(true)), spectral(nodes, elasticPlate(true, StepEstimate::Spectral));
  ASSERT_EQ(spectral.spectrumMeasurements(), 1);
  const auto& w = spectral.measuredFrequencies();
  ASSERT_GE(w.size(), 2u);
  for (std::size_t g = 1; g < w.size(); ++g) EXPECT_LE(w[g], w[g - 1]) << "a coarser group is no stiffer";
  EXPECT_DOUBLE_EQ(spectral.stableTimeStep(), ShellParameters{}.courantFactor * 2.0 / w.front());
  EXPECT_GT(spectral.stableTimeStep(), 2.0 * bound.stableTimeStep());
  for (std::size_t i = 0; i < spectral.size(); ++i) {
    if (spectral.clamped(i)) continue;
    EXPECT_GE(spectral.pointStableStep(i), spectral.stableTimeStep());
    EXPECT_LE(spectral.nodeStableStep(i), spectral.pointStableStep(i)) << "a node's step is its finest term's";
  }
  // The single rate measures the whole operator alone: the finest group's frequency and step.
  SphShell single(nodes, elasticPlate(false, StepEstimate::Spectral));
  ASSERT_EQ(single.measuredFrequencies().size(), 1u);
  EXPECT_EQ(single.measuredFrequencies().front(), w.front());
  EXPECT_EQ(single.stableTimeStep(), spectral.stableTimeStep());
}

struct Momentum {
  std::array<double, 3> linear{}, angular{};
  double scale = 0.0;  ///< Σ m |v| (linear) and Σ m |x| |v| (angular), for relative errors
  double angularScale = 0.0;
};

Momentum momentum(const SphShell& shell) {
  Momentum m;
  for (std::size_t i = 0; i < shell.size(); ++i) {
    const auto& x = shell.positions()[i];
    const auto& v = shell.velocities()[i];
    const auto& w = shell.spins()[i];
    const double mass = shell.mass(i), inertia = shell.rotaryInertia(i);
    const std::array<double, 3> xv = {x[1] * v[2] - x[2] * v[1], x[2] * v[0] - x[0] * v[2], x[0] * v[1] - x[1] * v[0]};
    for (int a = 0; a < 3; ++a) {
      m.linear[a] += mass * v[a];
      m.angular[a] += mass * xv[a] + inertia * w[a];
    }
    const double speed = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    m.scale += mass * speed;
    m.angularScale += mass * speed * std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  }
  return m;
}

/// A free stepped plate set vibrating and spinning: its momenta through 20 multi-rate intervals.
void expectMomentaKept(double hourglass, bool angularToo) {
  const ShellNodes nodes = steppedRefinedPlate(false);
  ShellParameters p = elasticPlate(true);
  p.hourglassCoefficient = hourglass;
  SphShell shell(nodes, p);
  for (std::size_t i = 0; i < shell.size(); ++i) {
    const double x = nodes.x[i], y = nodes.y[i];
    // A rigid spin about z, a drift, and a bending wave (deforms the plate across the step).
    const double w = 5.0e-3 * std::sin(40.0 * x) * std::cos(30.0 * y);
    shell.setNodeState(i, {x, y, 0.0}, {0.0, 0.0, 1.0}, {-50.0 * y + 0.3, 50.0 * x, 400.0 * w});
  }
  const Momentum before = momentum(shell);
  const double dt = interval(shell);
  for (int k = 0; k < 20; ++k) shell.advanceInterval(dt);
  ASSERT_GE(shell.stepClasses().coarsest, 2);
  const Momentum after = momentum(shell);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(after.linear[a], before.linear[a], 1e-12 * before.scale) << "linear momentum, axis " << a;
    if (angularToo) {
      EXPECT_NEAR(after.angular[a], before.angular[a], 1e-12 * before.angularScale) << "angular momentum, axis " << a;
    }
  }
}

TEST(ShellSubcycling, FreePlateKeepsItsMomentaThroughTheClassInterfaces) {
  // The stress points' forces are the exact derivatives of a frame-invariant energy: both momenta
  // are kept to round-off. The hourglass pairs' forces are equal and opposite, but their moment
  // is not zero (they take the direct part of the derivative only): linear momentum alone.
  expectMomentaKept(0.0, true);
  expectMomentaKept(ShellParameters{}.hourglassCoefficient, false);
}

TEST(ShellSubcycling, ResultIsIndependentOfTheThreadCount) {
  const ShellNodes nodes = steppedRefinedPlate();
  ShellParameters p = elasticPlate(true);
  p.plasticity = true;
  p.damage = true;
  for (StepEstimate estimate : {StepEstimate::Bound, StepEstimate::Spectral}) {
    p.stepEstimate = estimate;
    auto run = [&](int threads) {
      omp_set_num_threads(threads);
      SphShell shell(nodes, p);
      shell.setPressure(4.0e6);
      const double dt = interval(shell);
      for (int k = 0; k < 10; ++k) shell.advanceInterval(dt);
      return shell.positions();
    };
    const int previous = omp_get_max_threads();
    const auto one = run(1), two = run(2);
    omp_set_num_threads(previous);
    for (std::size_t i = 0; i < one.size(); ++i)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(one[i][c], two[i][c]) << "node " << i;
  }
}

}  // namespace
}  // namespace rupture
