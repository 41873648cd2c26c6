#include "calibration/strength_test.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace rupture {

namespace {

// Scales every element's displacement from x0 and its rotation by `factor`: the relaxed elastic
// state at strain ε_e becomes the equilibrium at factor × ε_e (the response is linear before any break).
void scaleDisplacements(ParticleStore& p, const ParticleStore& reference, double factor) {
  for (std::size_t k = 0; k < p.size(); ++k) {
    p.x[k] = reference.x[k] + factor * (p.x[k] - reference.x[k]);
    p.y[k] = reference.y[k] + factor * (p.y[k] - reference.y[k]);
    p.z[k] = reference.z[k] + factor * (p.z[k] - reference.z[k]);
    // Rotation vector θ = angle × axis of the orientation (references start at the identity).
    const double s = std::sqrt(p.qx[k] * p.qx[k] + p.qy[k] * p.qy[k] + p.qz[k] * p.qz[k]);
    if (s > 0) {
      const double angle = 2.0 * std::atan2(s, p.qw[k]) * factor;
      const double sh = std::sin(0.5 * angle) / s;
      p.qw[k] = std::cos(0.5 * angle);
      p.qx[k] *= sh; p.qy[k] *= sh; p.qz[k] *= sh;
    }
    p.vx[k] = p.vy[k] = p.vz[k] = 0;
    p.wx[k] = p.wy[k] = p.wz[k] = 0;
  }
}

}  // namespace

StrengthResult measureTensileStrength(const BondedSystem& sample, const SampleSpec& spec,
                                      const StrengthOptions& options) {
  if (!(sample.beam.failureStress > 0) || !std::isfinite(sample.beam.failureStress))
    throw CalibrationError("strength test: material.beam.failure_stress must be a finite number > 0");
  const auto cancelled = [&] { return options.elastic.cancel && options.elastic.cancel->load(std::memory_order_relaxed); };
  StrengthResult result;

  // Stage 1: the elastic field at ε_e, and the onset strain it implies.
  BondedSystem s;
  result.elastic = measureElasticProperties(sample, spec, options.elastic, &s);
  result.steps = result.elastic.steps;
  if (cancelled()) return result;
  const double sigmaF = sample.beam.failureStress;
  double worst = 0;  // largest σ_eq / (σ_f × the bond's strength factor) at ε_e
  const BondStore& loads = s.bondLoads();  // current for every law (central laws store none per step)
  for (std::size_t b = 0; b < s.bonds.size(); ++b)
    if (s.bonds.intact[b] > 0.5 && std::isfinite(s.bonds.strength[b]) && s.bonds.strength[b] > 0)
      worst = std::max(worst, loads.failureMeasure[b] / (sigmaF * s.bonds.strength[b]));
  if (!(worst > 0)) throw CalibrationError("strength test: no bond is loaded by the tension (cannot break)");
  const double strainE = options.elastic.strain;
  result.crackOnsetStrain = strainE / worst;

  // Stage 2: from half a step below the onset, strain steps with failure and contact on. The
  // first state is relaxed and recorded before any step (it is the elastic end of the curve), and
  // no step lands on ε_onset itself, where rounding alone decides whether the first bond breaks:
  // the sampled curve then scales with σ_f as the curve itself does.
  const double increment = options.strainIncrement * result.crackOnsetStrain;
  double strain = result.crackOnsetStrain - 0.5 * increment;
  scaleDisplacements(s.particles, sample.particles, strain / strainE);
  s.beam.failureStress = sigmaF;
  s.contact.setParameters(sample.contact.parameters());
  s.initialize();
  const double dt = options.elastic.timeStepSafety * s.criticalTimeStep();
  const TensionFaces faces = tensionFaces(s.particles);
  const double section = tensionSection(spec);
  double xc = 0;
  for (double x : sample.particles.x) xc += x;
  xc /= static_cast<double>(sample.particles.size());
  const std::size_t n = s.particles.size();
  const std::size_t interval =
      std::max<std::size_t>(200, static_cast<std::size_t>(4 * std::sqrt(static_cast<double>(n))));
  std::size_t broken = 0;
  const double initialBonds = static_cast<double>(s.bonds.size());
  const double maxStrain = options.maxStrainFactor * result.crackOnsetStrain;

  for (bool first = true; !cancelled(); first = false) {
    if (!first) {
      strain += increment;
      for (std::size_t k = 0; k < n; ++k) s.particles.x[k] += increment * (sample.particles.x[k] - xc);
    }
    ++result.increments;
    // Relax until σ̄ settles with no break over a whole interval.
    double previous = meanFaceStress(s.particles, faces, section);
    double stress = previous;
    for (std::size_t used = 0; used < options.maxStepsPerIncrement && !cancelled(); used += interval) {
      std::size_t brokenHere = 0;
      for (std::size_t k = 0; k < interval; ++k) {
        s.step(dt);
        brokenHere += s.brokenLastStep;
      }
      broken += brokenHere;
      stress = meanFaceStress(s.particles, faces, section);
      const double scale = std::max({std::abs(stress), result.tensileStrength, 1e-300});
      const bool settled = brokenHere == 0 && std::abs(stress - previous) < options.stressTolerance * scale;
      previous = stress;
      if (settled) break;
    }
    if (cancelled()) break;
    if (stress > result.tensileStrength) {
      result.tensileStrength = stress;
      result.strainAtPeak = strain;
      result.brokenFractionAtPeak = static_cast<double>(broken) / initialBonds;
    }
    if (options.elastic.progress)
      options.elastic.progress(std::clamp(strain / maxStrain, 0.0, 1.0));
    if ((broken > 0 && stress < options.stopFraction * result.tensileStrength) || strain >= maxStrain) {
      result.completed = true;
      break;
    }
  }
  result.steps += s.steps;
  return result;
}

StrengthFit fitFailureStress(const BondedSystem& sample, const SampleSpec& spec, double targetStrength,
                             const StrengthOptions& options, double relativeTolerance) {
  StrengthFit fit;
  BondedSystem trial = sample;
  const auto cancelled = [&] { return options.elastic.cancel && options.elastic.cancel->load(std::memory_order_relaxed); };
  auto test = [&](double sigmaF) {
    trial.beam.failureStress = sigmaF;
    ++fit.evaluations;
    return measureTensileStrength(trial, spec, options);
  };
  double sigmaA = sample.beam.failureStress;
  StrengthResult a = test(sigmaA);
  fit.failureStress = sigmaA;
  fit.achieved = a;
  if (cancelled()) { fit.cancelled = true; return fit; }
  if (!(a.tensileStrength > 0)) throw CalibrationError("strength fit: the sample carries no tensile stress");
  // The curve scales with σ_f: a proportional step, then secant steps on S(σ_f).
  double sigmaB = sigmaA * targetStrength / a.tensileStrength;
  for (int k = 0; k < 3; ++k) {
    const StrengthResult b = test(sigmaB);
    if (cancelled()) { fit.cancelled = true; fit.achieved = b; fit.failureStress = sigmaB; return fit; }
    if (std::abs(b.tensileStrength - targetStrength) < std::abs(fit.achieved.tensileStrength - targetStrength)) {
      fit.failureStress = sigmaB;
      fit.achieved = b;
    }
    if (std::abs(b.tensileStrength - targetStrength) <= relativeTolerance * targetStrength) break;
    const double slope = (b.tensileStrength - a.tensileStrength) / (sigmaB - sigmaA);
    const double next = slope > 0 ? sigmaB + (targetStrength - b.tensileStrength) / slope
                                  : sigmaB * targetStrength / b.tensileStrength;
    sigmaA = sigmaB; a = b;
    sigmaB = next > 0 ? next : sigmaB * targetStrength / b.tensileStrength;
  }
  return fit;
}

}  // namespace rupture
