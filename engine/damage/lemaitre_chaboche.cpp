#include "damage/lemaitre_chaboche.hpp"

#include <algorithm>
#include <cmath>

#include "core/format_number.hpp"
#include "rupture/spec_error.hpp"

namespace rupture {
double LemaitreChabocheDamage::delayedRate(double undelayed, double damage) const {
  const double gap = std::max(undelayed - damage, 0.0);
  return (1.0 - std::exp(-delaySharpness * gap)) / delayTime;
}

void validateDamage(const LemaitreChabocheDamage& d, const std::string& prefix) {
  if (!(std::isfinite(d.thresholdPlasticStrain) && d.thresholdPlasticStrain >= 0.0))
    throw SpecError(prefix + ".threshold_plastic_strain", formatNumber(d.thresholdPlasticStrain), "a strain >= 0");
  if (!(std::isfinite(d.criticalPlasticStrain) && d.criticalPlasticStrain > d.thresholdPlasticStrain))
    throw SpecError(prefix + ".critical_plastic_strain", formatNumber(d.criticalPlasticStrain),
                    "a strain > threshold_plastic_strain (" + formatNumber(d.thresholdPlasticStrain) + ")");
  if (!(d.criticalDamage > 0.0 && d.criticalDamage < 1.0))
    throw SpecError(prefix + ".critical_damage", formatNumber(d.criticalDamage), "a number in (0, 1)");
  if (!(std::isfinite(d.delayTime) && d.delayTime > 0.0))
    throw SpecError(prefix + ".delay_time", formatNumber(d.delayTime), "a time > 0 (s)");
  if (!(std::isfinite(d.delaySharpness) && d.delaySharpness > 0.0))
    throw SpecError(prefix + ".delay_sharpness", formatNumber(d.delaySharpness), "a number > 0");
  if (!(d.poissonRatio > -1.0 && d.poissonRatio < 0.5))
    throw SpecError(prefix + ".poisson_ratio", formatNumber(d.poissonRatio), "a number in (-1, 0.5)");
}

double energyReleaseRate(const LemaitreChabocheDamage& d, double effectiveVonMises,
                         double youngModulus, double eta) {
  return effectiveVonMises * effectiveVonMises * d.triaxialityFunction(eta) / (2.0 * youngModulus);
}

bool advanceDamage(const LemaitreChabocheDamage& d, DamageState& s, double p, double dp, double eta,
                   double dt) {
  if (s.fractured) return false;
  // Eqs. (9)–(11): only the part of the increment with R_ν p beyond ε_p^s damages.
  const double rnu = d.triaxialityFunction(eta);
  const double pOnset = d.thresholdPlasticStrain / rnu;
  const double active = std::max(0.0, p + dp - std::max(p, pOnset));
  s.undelayed += d.undelayedSlope() * rnu * active;
  // Eq. (12), backward Euler: g(D) = D − D_n − dt Ḋ(D_nc, D) = 0, increasing in D, g(D_n) <= 0,
  // g(D_nc) >= 0 when D_nc > D_n. Bisection to round-off (a few dozen iterations, no derivative
  // pitfalls near the kink of ⟨·⟩).
  if (s.undelayed > s.damage && dt > 0.0) {
    double lo = s.damage, hi = s.undelayed;
    const double dn = s.damage;
    auto residual = [&](double D) { return D - dn - dt * d.delayedRate(s.undelayed, D); };
    // The bisection's decisions are g(mid) < 0, i.e. mid below the root, wherever the rounding of
    // g cannot flip the sign: g' >= 1, so |g(mid)| >= |mid − root|, while g's rounding error is a
    // few ulps of its terms (<= 1 + dt/τ_c). A Newton estimate of the root (g is increasing and
    // convex: from the upper end it converges from above) decides the far midpoints without the
    // exponential; the near ones are evaluated as before. The same midpoints, the same decisions:
    // the same damage, bit for bit, at a fraction of the exponentials.
    const double margin = 1e-12 * (1.0 + dt / d.delayTime);
    double root = hi;
    bool converged = false;
    for (int it = 0; it < 30 && !converged; ++it) {
      const double e = std::exp(-d.delaySharpness * std::max(s.undelayed - root, 0.0));
      const double slope = 1.0 + dt * d.delaySharpness * e / d.delayTime;
      const double step = residual(root) / slope;
      root -= step;
      converged = std::abs(step) < 1e-3 * margin;
    }
    for (int it = 0; it < 80 && hi - lo > 1e-16; ++it) {
      const double mid = 0.5 * (lo + hi);
      const bool below = (converged && std::abs(mid - root) > margin) ? mid < root : residual(mid) < 0.0;
      if (below) lo = mid; else hi = mid;
    }
    s.damage = lo;  // the lower end: the rate bound (D − D_n)/dt <= 1/τ_c holds exactly
  }
  if (s.damage >= d.criticalDamage) {
    s.damage = d.criticalDamage;
    s.fractured = true;
    return true;
  }
  return false;
}

void advanceDamage(const LemaitreChabocheDamage& d, std::span<DamageState> states,
                   std::span<const double> plasticStrain, std::span<const double> dp,
                   std::span<const double> eta, double dt) {
  for (std::size_t i = 0; i < states.size(); ++i)
    advanceDamage(d, states[i], plasticStrain[i], dp[i], eta[i], dt);
}

}  // namespace rupture
