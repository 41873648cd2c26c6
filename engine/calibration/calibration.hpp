#pragma once
// Calibration of the cohesive beams (André et al. 2012, §4; docs/references.md#eq-calibration).
//
// Measurement: a quasi-static uniaxial tension on a built sample. Every element starts on the
// affine field u = ε (x − x_c) e_x − ν₀ ε (y − y_c) e_y (− ν₀ ε (z − z_c) e_z), the faces X_min and
// X_max are then held in x (free laterally), and Cundall-damped dynamics relaxes the interior to
// equilibrium (no failure, no contact). Then
//   E = σ̄ / ε with σ̄ = ½(F_Xmin + F_Xmax)/S (S = L_y × t in 2D with t = R_DE, L_y × L_z in 3D),
//   ν = −ε_lat / ε with ε_lat the least-squares slope of u_y(y) (and u_z(z), averaged, in 3D).
// Fit: ν_M depends almost only on the beam radius ratio (decreasing), E_M is linear in E_μ: find the
// radius ratio for the target ν by bracketing and regula falsi, then rescale E_μ by E_target / E_M.
#include <atomic>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "bonded/bonded_system.hpp"
#include "samples/sample_builder.hpp"
#include "bonded/sample_spec.hpp"

namespace rupture {

class TestJournal;

struct ElasticProperties {
  double youngModulus = 0;  ///< Pa
  double poissonRatio = 0;  ///< 1
  std::size_t steps = 0;    ///< relaxation steps used
  bool converged = false;
};

struct CalibrationOptions {
  double strain = 1e-4;        ///< imposed ε (1)
  double damping = 0.7;        ///< Cundall local damping γ
  double timeStepSafety = 0.3; ///< quasi-static: no wave accuracy needed
  double tolerance = 2e-5;     ///< relative change of E and ν between checks to stop
  std::size_t maxSteps = 400000;
  /// When given and set, a measurement stops at its next check interval (returning the current,
  /// unconverged values) and a fit runs no further tension test (it returns what it has).
  const std::atomic<bool>* cancel = nullptr;
  /// When given, called after each convergence check of a measurement with its estimated fraction
  /// done in [0, 1] (not necessarily monotone; the relaxation has no known length).
  std::function<void(double)> progress;
  /// When given, the run's checkpoints (test_journal.hpp): finished tests are replayed from it and
  /// the test under way is checkpointed and resumed through it.
  TestJournal* journal = nullptr;
};

/// True when a test should stop before its next step: options.cancel set, or the run's
/// checkpoints (options.journal, told the test's own step count) say stop.
bool stopBeforeStep(const CalibrationOptions& options, std::uint64_t testSteps);
/// True once a test was stopped: a fit runs no further test.
bool testsStopped(const CalibrationOptions& options);

/// Thrown when a target cannot be reached (the message names the option and the reachable range).
class CalibrationError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Measures E and ν of a built sample (the system is copied; the original is untouched; the
/// relaxation is elastic_relaxation.hpp).
ElasticProperties measureElasticProperties(const BondedSystem& sample, const SampleSpec& spec,
                                           const CalibrationOptions& options = {});

/// The elements of the X_min and X_max faces of a tension test: those whose surface lies within half
/// a mean radius of the extreme x.
struct TensionFaces {
  std::vector<std::size_t> xmin, xmax;
};
TensionFaces tensionFaces(const ParticleStore& p);

/// The section S of Longchamp et al. 2024's eq. 4: L_y × t in 2D (t = spec.thickness, else R_DE),
/// L_y × L_z in 3D (m²).
double tensionSection(const SampleSpec& spec);

/// σ̄ = ½ (F_Xmin + F_Xmax) / S from the bond and contact forces on the face elements (Pa).
double meanFaceStress(const ParticleStore& p, const TensionFaces& faces, double section);

struct BeamFit {
  BeamParameters beam;          ///< fitted E_μ and radius ratio (ν_μ and σ_f kept)
  ElasticProperties achieved;   ///< re-measured with the fitted beams
  int evaluations = 0;          ///< number of tension tests run
  bool cancelled = false;       ///< options.cancel was set: the fit stopped early; beam is the fitted
                                ///< one only if the last test was reached, achieved the last test's values
};

/// Upper bound on the tension tests of one fitBeamParameters call (for progress estimates).
constexpr int kMaxFitEvaluations = 1 + 12 + 10 + 1;

/// Fits the beam Young's modulus and radius ratio so that the sample reaches targetYoung (Pa) and
/// targetPoisson. Throws CalibrationError if ν is out of reach for radius ratios in [0.02, 1].
/// On cancel (options.cancel set) it returns early with cancelled = true. options.progress, when
/// given, receives the fraction of the fit's test budget (kMaxFitEvaluations) done.
BeamFit fitBeamParameters(const BondedSystem& sample, const SampleSpec& spec, double targetYoung,
                          double targetPoisson, const CalibrationOptions& options = {});

}  // namespace rupture
