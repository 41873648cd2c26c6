#pragma once
// Multi-rate time stepping of the SPH shell: nodal subcycling by power-of-two time-step classes
// (Belytschko, Yen & Mullen 1979; Daniel 1997; LS-DYNA's *CONTROL_SUBCYCLE), in the impulse form of
// the asynchronous variational integrators (Lew, Marsden, Ortiz & West 2003).
//
// An interval (one fluid step) is cut into K fine steps δ. Each force term is evaluated every 2^c
// fine steps and gives its nodes the impulse of those 2^c δ at once; every node drifts (x += δ v,
// the director turns) at every fine step. A term's class c is the largest c ≤ C with 2^c δ no
// longer than its own critical step:
//   - a stress point's: the shortest over the nodes its kernel reaches of its stiffness against
//     their mass and rotary inertia (SphShell::pointStableStep);
//   - an hourglass pair's: the finer of its two nodes' (SphShell::nodeStableStep, the shortest of
//     the terms that reach a node).
// Each term's forces sum to zero and have no net moment (its energy depends on differences of
// positions and is frame-invariant), so the impulses keep linear momentum whatever the classes;
// with every class 0 the scheme is the single-rate central difference, bit for bit (the weights
// 2^c multiply exactly). K is a multiple of 2^C, so every term fires at the interval's start and
// the classes are in step again at its end: the fluid–shell exchange stays once per fluid step.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rupture {

/// The coarsest class allowed: 2^6 = 64 fine steps (more gains nothing: the finest class's cost
/// dominates long before).
inline constexpr int kMaxStepClass = 6;

/// 2^c, the weight of a term of class c (exact; an integer conversion, not a call to std::ldexp in
/// the loops over the pairs).
inline double classWeight(int c) { return static_cast<double>(1u << c); }

/// How an interval is cut: K fine steps of δ = interval / K, classes up to `coarsest`.
struct SubcyclingPlan {
  long fineSteps = 1;
  int coarsest = 0;
  double fineStep = 0.0;
};

/// The plan of least cost (fewest stress-point evaluations, Σ_i K / 2^{c_i}) over C = 0, 1, …
/// with 2^C ≤ ⌈interval / stableStep⌉: K = ⌈interval / stableStep⌉ rounded up to a multiple of
/// 2^C. `stableStep` is the single-rate step (no longer than any point's). C = 0 is the single rate.
/// `multiRateStep` (0: stableStep), the finest of `pointStep`, sets K of the plans with C ≥ 1
/// where the points' steps for the multi-rate scheme are shorter than the single rate's (below).
SubcyclingPlan planSubcycling(const std::vector<double>& pointStep, double stableStep, double interval,
                              double multiRateStep = 0.0);

/// The largest fraction of a class's critical step (2/ω of its terms) the multi-rate scheme takes
/// when the critical step is measured (SphShell's spectral estimate). A term of class c + 1 gives
/// the nodes it shares with class c an impulse every 2^{c+1} δ: a mean force plus one that
/// alternates from step to step of the class, at its Nyquist frequency, to which the central
/// difference answers with an oscillation (ω h)²/(4 − (ω h)²) times the static response to it (h =
/// 2^c δ, ω its class's largest frequency): 1.8 at ω h = 1.6 (the Courant factor 0.8), 1/3 at
/// ω h = 1 (this factor), 0.02 at the bound's ω h ≈ 0.27 (its estimate is 5.8 times the measured
/// frequency on the seed's TF14A5 plate). Measured on the seed's TF14A5 (docs/shell-and-damage.md):
/// subcycled at 0.8 of the measured limit the first pressure peak came 1.7 % low and the plate tore
/// 0.28 ms early; at 0.5, the single rate's peak within 0.01 %.
inline constexpr double kMultiRateCourantFactor = 0.5;

/// The class of each node, stress point and node force for a plan, and the nodes sorted by class.
struct ShellStepClasses {
  int coarsest = 0;
  std::vector<std::uint8_t> node;    ///< node i's own class (its hourglass pairs take the finer of two)
  std::vector<std::uint8_t> point;   ///< stress point i's class
  std::vector<std::uint8_t> gather;  ///< node i's force: the finest term that reaches it
  std::vector<std::uint32_t> pointOrder, gatherOrder;  ///< node indices by class, then index
  /// pointsUpTo[c]: how many points have a class ≤ c (the first ones of pointOrder); the same for gather.
  std::array<std::size_t, kMaxStepClass + 1> pointsUpTo{}, gatherUpTo{};

  /// Every node, point and force in class 0 (the single-rate scheme) for n nodes.
  void assignSingleRate(std::size_t n);
  /// The classes of `plan` from the nodes' and points' own steps and the kernel neighbourhoods
  /// (CSR: node i's neighbours are neighbour[offset[i] .. offset[i + 1])). Returns false when
  /// nothing changed.
  bool assign(const std::vector<double>& nodeStep, const std::vector<double>& pointStep, const SubcyclingPlan& plan,
              const std::vector<std::size_t>& offset, const std::vector<std::size_t>& neighbour);
  bool singleRate() const { return coarsest == 0; }
};

/// The stress points in each class, "class: count" pairs of the classes that have points
/// ("0: 1512, 2: 6340"): the run summary's shell_points_per_class.
std::string pointsPerClass(const ShellStepClasses& classes);

/// The largest class that fires at fine step k of an interval (k = 0: all of them): the number of
/// trailing zero bits of k, at most `coarsest`.
inline int firingClass(long k, int coarsest) {
  int c = 0;
  while (c < coarsest && (k & (1L << c)) == 0) ++c;
  return c;
}

}  // namespace rupture
