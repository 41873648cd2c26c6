#include "calibration/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "calibration/elastic_relaxation.hpp"
#include "calibration/test_journal.hpp"

namespace rupture {

bool stopBeforeStep(const CalibrationOptions& options, std::uint64_t testSteps) {
  // The journal's poll sees cancel too (and may checkpoint first); without one, cancel alone.
  if (options.journal) return options.journal->poll(testSteps);
  return options.cancel && options.cancel->load(std::memory_order_relaxed);
}

bool testsStopped(const CalibrationOptions& options) {
  return (options.cancel && options.cancel->load(std::memory_order_relaxed)) ||
         (options.journal && options.journal->stopped());
}

TensionFaces tensionFaces(const ParticleStore& p) {
  double lo = 1e300, hi = -1e300, mean = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    lo = std::min(lo, p.x[k] - p.radius[k]);
    hi = std::max(hi, p.x[k] + p.radius[k]);
    mean += p.radius[k];
  }
  mean /= static_cast<double>(p.size());
  TensionFaces g;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (p.x[k] - p.radius[k] <= lo + 0.5 * mean) g.xmin.push_back(k);
    else if (p.x[k] + p.radius[k] >= hi - 0.5 * mean) g.xmax.push_back(k);
  }
  return g;
}

double tensionSection(const SampleSpec& spec) {
  const double thickness =
      spec.dimension == 2 ? (spec.thickness > 0 ? spec.thickness : spec.elementRadius) : spec.size[2];
  return spec.size[1] * thickness;
}

double meanFaceStress(const ParticleStore& p, const TensionFaces& faces, double section) {
  double fMin = 0, fMax = 0;
  for (std::size_t k : faces.xmin) fMin += p.fx[k];
  for (std::size_t k : faces.xmax) fMax -= p.fx[k];
  return 0.5 * (fMin + fMax) / section;
}

ElasticProperties measureElasticProperties(const BondedSystem& sample, const SampleSpec& spec,
                                           const CalibrationOptions& options) {
  TestJournal* journal = options.journal;
  if (journal)
    if (const auto recorded = journal->replay<ElasticProperties>()) return *recorded;
  ElasticRelaxation relaxation(sample, spec, options);
  if (journal) journal->begin([&relaxation](StateArchive& archive) { relaxation.exchangeState(archive); });
  const ElasticProperties measured = relaxation.run();
  if (journal && !relaxation.stopped()) journal->finish(measured, measured.steps);
  return measured;
}

BeamFit fitBeamParameters(const BondedSystem& sample, const SampleSpec& spec, double targetYoung,
                          double targetPoisson, const CalibrationOptions& options) {
  BeamFit fit;
  fit.beam = sample.beam;
  BondedSystem trial = sample;
  struct Cancelled {};  // unwinds the fit between tension tests
  auto cancelled = [&] { return testsStopped(options); };
  // One tension test; the caller's progress sees the fraction of the fit's test budget.
  auto measureTrial = [&] {
    if (cancelled()) throw Cancelled{};
    CalibrationOptions inner = options;
    const int done = fit.evaluations++;
    if (options.progress)
      inner.progress = [&options, done](double f) { options.progress((done + f) / kMaxFitEvaluations); };
    const ElasticProperties measured = measureElasticProperties(trial, spec, inner);
    if (cancelled()) {
      fit.achieved = measured;
      throw Cancelled{};
    }
    if (options.progress) options.progress(static_cast<double>(done + 1) / kMaxFitEvaluations);
    return measured;
  };
  auto evaluate = [&](double ratio) {
    trial.beam.radiusRatio = ratio;
    return measureTrial();
  };
  try {
    constexpr double kMinRatio = 0.02, kMaxRatio = 1.0;
    // ν_M falls as the radius ratio grows: bracket the target, then regula falsi on ν(ratio).
    double a = std::clamp(sample.beam.radiusRatio, kMinRatio, kMaxRatio);
    ElasticProperties pa = evaluate(a);
    double b = a;
    ElasticProperties pb = pa;
    const double direction = pa.poissonRatio > targetPoisson ? 1.5 : 1.0 / 1.5;
    for (int k = 0; k < 12 && (pb.poissonRatio - targetPoisson) * (pa.poissonRatio - targetPoisson) > 0; ++k) {
      a = b; pa = pb;
      const double next = std::clamp(b * direction, kMinRatio, kMaxRatio);
      if (next == b) {
        std::ostringstream msg;
        msg << "--target-poisson-ratio " << targetPoisson << " is out of reach on this sample: radius ratio "
            << b << " gives " << pb.poissonRatio << " (the beams' Poisson ratio falls as the radius ratio grows, "
            << "from about 0.25 at small ratios)";
        throw CalibrationError(msg.str());
      }
      b = next;
      pb = evaluate(b);
    }
    ElasticProperties best = std::abs(pa.poissonRatio - targetPoisson) < std::abs(pb.poissonRatio - targetPoisson) ? pa : pb;
    double bestRatio = best.poissonRatio == pa.poissonRatio ? a : b;
    for (int k = 0; k < 10 && std::abs(best.poissonRatio - targetPoisson) > 2e-3; ++k) {
      const double c = a + (targetPoisson - pa.poissonRatio) * (b - a) / (pb.poissonRatio - pa.poissonRatio);
      const ElasticProperties pc = evaluate(c);
      if (std::abs(pc.poissonRatio - targetPoisson) < std::abs(best.poissonRatio - targetPoisson)) {
        best = pc;
        bestRatio = c;
      }
      if ((pc.poissonRatio - targetPoisson) * (pa.poissonRatio - targetPoisson) > 0) { a = c; pa = pc; }
      else { b = c; pb = pc; }
    }
    // E_M is proportional to E_μ at a fixed radius ratio.
    fit.beam = sample.beam;
    fit.beam.radiusRatio = bestRatio;
    fit.beam.youngModulus = sample.beam.youngModulus * targetYoung / best.youngModulus;
    trial.beam = fit.beam;
    fit.achieved = measureTrial();
  } catch (const Cancelled&) {
    fit.cancelled = true;
  }
  return fit;
}

}  // namespace rupture
