#include "calibration/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace rupture {

namespace {

constexpr double kInitialPoissonGuess = 0.25;

// Least-squares slope of u(c) over all elements.
double slope(const std::vector<double>& c, const std::vector<double>& u) {
  double mc = 0, mu = 0;
  for (std::size_t k = 0; k < c.size(); ++k) { mc += c[k]; mu += u[k]; }
  mc /= static_cast<double>(c.size());
  mu /= static_cast<double>(c.size());
  double num = 0, den = 0;
  for (std::size_t k = 0; k < c.size(); ++k) {
    num += (c[k] - mc) * (u[k] - mu);
    den += (c[k] - mc) * (c[k] - mc);
  }
  return den > 0 ? num / den : 0.0;
}

}  // namespace

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
                                           const CalibrationOptions& options, BondedSystem* relaxed) {
  BondedSystem s = sample;
  ParticleStore& p = s.particles;
  const std::size_t n = p.size();
  if (n < 4) throw CalibrationError("calibration needs a sample of at least 4 elements");
  s.beam.failureStress = 0;  // unbreakable: an elastic measurement
  ContactParameters noContact = s.contact.parameters();
  noContact.enabled = false;
  s.contact.setParameters(noContact);
  s.localDamping = options.damping;
  s.prescribe = nullptr;

  const TensionFaces faces = tensionFaces(p);
  if (faces.xmin.empty() || faces.xmax.empty()) throw CalibrationError("calibration: sample has no X faces");
  const std::vector<double> x0 = p.x, y0 = p.y, z0 = p.z;
  double xc = 0, yc = 0, zc = 0;
  for (std::size_t k = 0; k < n; ++k) { xc += x0[k]; yc += y0[k]; zc += z0[k]; }
  xc /= static_cast<double>(n); yc /= static_cast<double>(n); zc /= static_cast<double>(n);

  const double eps = options.strain;
  for (std::size_t k = 0; k < n; ++k) {
    p.x[k] = x0[k] + eps * (x0[k] - xc);
    p.y[k] = y0[k] - kInitialPoissonGuess * eps * (y0[k] - yc);
    if (p.dimension == 3) p.z[k] = z0[k] - kInitialPoissonGuess * eps * (z0[k] - zc);
    p.vx[k] = p.vy[k] = p.vz[k] = 0;
    p.fixedDofs[k] = 0;
  }
  for (std::size_t k : faces.xmin) p.fixedDofs[k] = kFixX;
  for (std::size_t k : faces.xmax) p.fixedDofs[k] = kFixX;
  s.initialize();
  const double dt = options.timeStepSafety * s.criticalTimeStep();

  const double section = tensionSection(spec);

  auto measure = [&]() {
    const double stress = meanFaceStress(p, faces, section);
    std::vector<double> uy(n), uz(n);
    for (std::size_t k = 0; k < n; ++k) { uy[k] = p.y[k] - y0[k]; uz[k] = p.z[k] - z0[k]; }
    double lateral = slope(y0, uy);
    if (p.dimension == 3) lateral = 0.5 * (lateral + slope(z0, uz));
    return ElasticProperties{stress / eps, -lateral / eps, s.steps, false};
  };

  // Relax until E and ν change by less than the tolerance over a check interval (a few wave
  // transits of the sample, counted in steps from the element count across).
  const double across = std::sqrt(static_cast<double>(n));
  const std::size_t interval = std::max<std::size_t>(200, static_cast<std::size_t>(4 * across));
  // Cancel is polled every step (one relaxed load), so a large sample stops within one step.
  auto cancelled = [&] { return options.cancel && options.cancel->load(std::memory_order_relaxed); };
  ElasticProperties previous = measure(), current = previous;
  double firstChange = 0;  // the change at the first check, for the progress estimate
  while (s.steps < options.maxSteps && !cancelled()) {
    for (std::size_t k = 0; k < interval && !cancelled(); ++k) s.step(dt);
    if (cancelled()) break;
    current = measure();
    const double dE = std::abs(current.youngModulus - previous.youngModulus) / std::abs(current.youngModulus);
    const double dNu = std::abs(current.poissonRatio - previous.poissonRatio);
    if (dE < options.tolerance && dNu < options.tolerance) {
      current.converged = true;
      break;
    }
    if (options.progress) {
      // The changes fall roughly geometrically: estimate the fraction done on a log scale
      // between the first change and the tolerance, bounded by the step budget.
      const double change = std::max({dE, dNu, options.tolerance});
      if (firstChange == 0) firstChange = std::max(change, options.tolerance * 1.0001);
      const double byChange = std::log(firstChange / change) / std::log(firstChange / options.tolerance);
      const double bySteps = static_cast<double>(s.steps) / static_cast<double>(options.maxSteps);
      options.progress(std::clamp(std::max(byChange, bySteps), 0.0, 1.0));
    }
    previous = current;
  }
  current.steps = s.steps;
  if (relaxed) *relaxed = std::move(s);
  return current;
}

BeamFit fitBeamParameters(const BondedSystem& sample, const SampleSpec& spec, double targetYoung,
                          double targetPoisson, const CalibrationOptions& options) {
  BeamFit fit;
  fit.beam = sample.beam;
  BondedSystem trial = sample;
  struct Cancelled {};  // unwinds the fit between tension tests
  auto cancelled = [&] { return options.cancel && options.cancel->load(std::memory_order_relaxed); };
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
