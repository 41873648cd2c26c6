#include "calibration/strength_test.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "calibration/elastic_relaxation.hpp"
#include "calibration/test_journal.hpp"

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

// The test, held as a state a checkpoint can take mid-way (test_journal.hpp): stage 1 is the
// elastic relaxation; stage 2 the strain steps, with where the loop stands in its members.
class StrengthTest {
public:
  StrengthTest(const BondedSystem& sample, const SampleSpec& spec, const StrengthOptions& options)
      : m_sample(sample), m_spec(spec), m_options(options), m_relaxation(sample, spec, options.elastic) {}

  StrengthResult run();
  bool stopped() const { return m_stopped; }
  std::uint64_t steps() const { return m_relaxation.system().steps; }

  void exchangeState(StateArchive& archive) {
    StateGroup group(archive, "strength_test");
    archive.value("stage", m_stage);
    archive.record("result", m_result);
    if (m_stage == 1) {
      m_relaxation.exchangeState(archive);
      return;
    }
    // Stage 2's set-up (thresholds, contact) is not in the checkpoint: made again before loading.
    if (archive.loading()) armForFailure();
    m_relaxation.system().exchangeState(archive);
    archive.value("dt", m_dt);
    archive.array("face_xmin", m_faces.xmin);
    archive.array("face_xmax", m_faces.xmax);
    archive.value("strain", m_strain);
    archive.value("in_increment", m_inIncrement);
    archive.value("steps_in_increment", m_used);
    archive.value("steps_in_interval", m_inInterval);
    archive.value("broken", m_broken);
    archive.value("broken_in_interval", m_brokenHere);
    archive.value("previous_stress", m_previous);
    archive.value("stress", m_stress);
  }

private:
  /// Failure on at the sample's σ_f, the sample's contact: the damage stage's system.
  void armForFailure() {
    BondedSystem& s = m_relaxation.system();
    s.beam.failureStress = m_sample.beam.failureStress;
    s.contact.setParameters(m_sample.contact.parameters());
    s.initialize();
  }
  /// Stage 1 done: the onset strain, and the damage stage set up from half a step below it.
  void beginDamageStage();
  StrengthResult stoppedResult() {
    m_stopped = true;
    m_result.steps = m_result.elastic.steps + steps();
    return m_result;
  }

  const BondedSystem& m_sample;
  const SampleSpec& m_spec;
  const StrengthOptions& m_options;
  ElasticRelaxation m_relaxation;
  int m_stage = 1;
  StrengthResult m_result;
  // Stage 2: its set-up and where its loop stands.
  double m_dt = 0, m_strain = 0;
  TensionFaces m_faces;
  bool m_inIncrement = false;
  std::size_t m_used = 0, m_inInterval = 0, m_broken = 0, m_brokenHere = 0;
  double m_previous = 0, m_stress = 0;
  bool m_stopped = false;
};

void StrengthTest::beginDamageStage() {
  BondedSystem& s = m_relaxation.system();
  const double sigmaF = m_sample.beam.failureStress;
  double worst = 0;  // largest σ_eq / (σ_f × the bond's strength factor × its first fibre's factor) at ε_e
  const BondStore& loads = s.bondLoads();  // current for every law (central laws store none per step)
  for (std::size_t b = 0; b < s.bonds.size(); ++b)
    if (s.bonds.intact[b] > 0.0 && std::isfinite(s.bonds.strength[b]) && s.bonds.strength[b] > 0)
      worst = std::max(worst, loads.failureMeasure[b] / (sigmaF * s.bonds.strength[b] * s.bonds.firstDamageFactor(b)));
  if (!(worst > 0)) throw CalibrationError("strength test: no bond is loaded by the tension (cannot break)");
  const double strainE = m_options.elastic.strain;
  m_result.crackOnsetStrain = strainE / worst;

  // From half a step below the onset, strain steps with failure and contact on. The first state is
  // relaxed and recorded before any step (it is the elastic end of the curve), and no step lands on
  // ε_onset itself, where rounding alone decides whether the first bond breaks: the sampled curve
  // then scales with σ_f as the curve itself does.
  const double increment = m_options.strainIncrement * m_result.crackOnsetStrain;
  m_strain = m_result.crackOnsetStrain - 0.5 * increment;
  scaleDisplacements(s.particles, m_sample.particles, m_strain / strainE);
  armForFailure();
  m_dt = m_options.elastic.timeStepSafety * s.criticalTimeStep();
  m_faces = tensionFaces(s.particles);
  m_inIncrement = false;
  m_stage = 2;
}

StrengthResult StrengthTest::run() {
  if (m_stage == 1) {
    m_result.elastic = m_relaxation.run();
    m_result.steps = m_result.elastic.steps;
    if (m_relaxation.stopped()) {
      m_stopped = true;
      return m_result;
    }
    beginDamageStage();
  }
  BondedSystem& s = m_relaxation.system();
  const CalibrationOptions& elastic = m_options.elastic;
  const double increment = m_options.strainIncrement * m_result.crackOnsetStrain;
  const double section = tensionSection(m_spec);
  double xc = 0;
  for (double x : m_sample.particles.x) xc += x;
  xc /= static_cast<double>(m_sample.particles.size());
  const std::size_t n = s.particles.size();
  const std::size_t interval =
      std::max<std::size_t>(200, static_cast<std::size_t>(4 * std::sqrt(static_cast<double>(n))));
  const double initialBonds = static_cast<double>(s.bonds.size());
  const double maxStrain = m_options.maxStrainFactor * m_result.crackOnsetStrain;

  while (true) {
    if (!m_inIncrement) {
      if (m_result.increments > 0) {
        m_strain += increment;
        for (std::size_t k = 0; k < n; ++k) s.particles.x[k] += increment * (m_sample.particles.x[k] - xc);
      }
      ++m_result.increments;
      m_previous = m_stress = meanFaceStress(s.particles, m_faces, section);
      m_used = m_inInterval = m_brokenHere = 0;
      m_inIncrement = true;
    }
    // Relax until σ̄ settles with no break over a whole interval.
    while (m_used < m_options.maxStepsPerIncrement) {
      for (; m_inInterval < interval; ++m_inInterval) {
        if (stopBeforeStep(elastic, steps())) return stoppedResult();
        s.step(m_dt);
        m_brokenHere += s.brokenLastStep;
      }
      m_broken += m_brokenHere;
      m_stress = meanFaceStress(s.particles, m_faces, section);
      const double scale = std::max({std::abs(m_stress), m_result.tensileStrength, 1e-300});
      const bool settled = m_brokenHere == 0 && std::abs(m_stress - m_previous) < m_options.stressTolerance * scale;
      m_previous = m_stress;
      m_inInterval = m_brokenHere = 0;
      m_used += interval;
      if (settled) break;
    }
    m_inIncrement = false;
    if (m_stress > m_result.tensileStrength) {
      m_result.tensileStrength = m_stress;
      m_result.strainAtPeak = m_strain;
      m_result.brokenFractionAtPeak = static_cast<double>(m_broken) / initialBonds;
    }
    if (elastic.progress) elastic.progress(std::clamp(m_strain / maxStrain, 0.0, 1.0));
    if ((m_broken > 0 && m_stress < m_options.stopFraction * m_result.tensileStrength) || m_strain >= maxStrain) {
      m_result.completed = true;
      break;
    }
  }
  m_result.steps += steps();
  return m_result;
}

}  // namespace

StrengthResult measureTensileStrength(const BondedSystem& sample, const SampleSpec& spec,
                                      const StrengthOptions& options) {
  if (!(sample.beam.failureStress > 0) || !std::isfinite(sample.beam.failureStress))
    throw CalibrationError("strength test: material.beam.failure_stress must be a finite number > 0");
  TestJournal* journal = options.elastic.journal;
  if (journal)
    if (const auto recorded = journal->replay<StrengthResult>()) return *recorded;
  StrengthTest test(sample, spec, options);
  if (journal) journal->begin([&test](StateArchive& archive) { test.exchangeState(archive); });
  const StrengthResult result = test.run();
  if (journal && !test.stopped()) journal->finish(result, test.steps());
  return result;
}

StrengthFit fitFailureStress(const BondedSystem& sample, const SampleSpec& spec, double targetStrength,
                             const StrengthOptions& options, double relativeTolerance) {
  StrengthFit fit;
  BondedSystem trial = sample;
  const auto cancelled = [&] { return testsStopped(options.elastic); };
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
