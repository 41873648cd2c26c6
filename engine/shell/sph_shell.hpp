#pragma once
// Meshless (SPH) Mindlin–Reissner shell after Maurel & Combescure (2008) and Caleyron et al. (2011,
// 2013 §5.4.1; docs/references.md): one layer of nodes in the mid-surface, each with a position x and a
// pseudo-normal (director) n (5 degrees of freedom: no drilling rotation), a total-Lagrangian
// corrected kernel, plane-stress plasticity and damage integrated through the thickness.
//
// Kinematics (seed eq. 15): x(X, ξ) = x_m(X) + ξ n(X). With the corrected gradients on the flat
// reference (first-order consistent, equivalent to linear-basis MLS derivatives):
//   A_α = ∂x_m/∂X_α = Σ_j V_j (x_j − x_i) B_ijα,   G_α = ∂n/∂X_α = Σ_j V_j (n_j − n_i) B_ijα,
//   B_ij = M_i⁻ᵀ ∇W(X_i − X_j),   M_i = Σ_j V_j (X_j − X_i) ⊗ ∇W(X_i − X_j)
// Green–Lagrange strains of a Reissner–Mindlin shell (large rotations, small strains):
//   membrane ε_αβ = ½ (A_α·A_β − δ_αβ),  curvature κ_αβ = ½ (A_α·G_β + A_β·G_α),
//   transverse shear γ (continuum: A_α·n) from the pairs: γ_i = T_i⁻¹ Σ_j V_j W_ij s_ij X_ij,
//   s_ij = (x_j − x_i)·(n_i + n_j)/|n_i + n_j|, T_i = Σ_j V_j W_ij X_ij ⊗ X_ij (locking-free)
// Layer k at ξ_k: E = ε + ξ_k κ → plane-stress return mapping → S_k (2nd Piola–Kirchhoff), times
// (1 − D_k); resultants N = Σ w_k S_k, M = Σ w_k ξ_k S_k, Q = κ_s G t γ (elastic, scaled by the
// mean (1 − D) of the layers).
// Forces are the exact derivatives of the discrete energy Σ_i ω_i (N:ε + M:κ + Q·γ)-increments
// (stress points at the nodes, quadrature weights ω_i), so the scheme conserves energy and momentum.
// Nodal integration leaves zero-energy (checkerboard) modes: they are held by a pair-wise
// hourglass control after Ganzenmüller (2015), which penalises the difference between the actual
// separation of a pair and the one predicted by the mean gradient of its two nodes (exact for
// quadratic fields, so it does not stiffen smooth bending).
//
// Fracture (Caleyron et al. 2011): once ShellParameters::fractureLayerFraction of a stress point's
// layers have reached D_c (by default every layer), the stress point is dropped, its node's links
// are cut, the links between other nodes whose segment crosses its cell (disc of radius √V/2) are
// cut (visibility criterion), and the corrected gradients are rebuilt (free edges follow: the
// correction only uses the neighbours that remain). A node left without a valid gradient becomes a
// fragment (moves freely, carries no stress).
#include <array>
#include <cstdint>
#include <vector>

#include "core/cancellation.hpp"
#include "damage/lemaitre_chaboche.hpp"
#include "shell/shell_nodes.hpp"
#include "shell/shell_parameters.hpp"
#include "shell/step_classes.hpp"
#include "shell/shell_vector.hpp"
#include "shell/through_thickness.hpp"
#include "rupture/state_archive.hpp"

namespace rupture {

/// The spectral step estimate (ShellParameters::StepEstimate::Spectral): power iterations per
/// measurement of a group's largest frequency, and the share of the nodes (1/this) whose
/// gradients a fracture must have rebuilt before advanceInterval measures again.
inline constexpr int kSpectrumIterations = 30;
inline constexpr std::size_t kSpectrumRemeasureFraction = 64;

class SphShell {
public:
  SphShell(const ShellNodes& nodes, const ShellParameters& params);

  /// Uniform pressure (Pa) on the free part of the shell; positive along the current normal
  /// A_1 × A_2 (+z in the reference). The force follows the deformed area (a follower load).
  void setPressure(double p) { m_pressure = p; }

  /// External force on node i (N), added to the internal forces at every step until changed:
  /// the hook for fluid–structure contact and other loads given per node.
  void setExternalForce(std::size_t i, const ShellVec3& force) { m_external.at(i) = force; }
  /// Integration area ω_i of node i (m²): the mid-surface area it represents.
  double integrationArea(std::size_t i) const { return m_area[i]; }

  /// Estimated critical time step (s) times the Courant factor: the largest frequency of the
  /// membrane/shear translation and of the rotation (bending + transverse shear against the
  /// rotary inertia) over the node spacing (see docs/shell-and-damage.md, "Time step").
  double stableTimeStep() const { return m_stableStep; }

  /// Sets the state of node i (initial conditions, prescribed motion of clamped nodes): position
  /// (m), pseudo-normal (normalised here) and velocity (m/s).
  void setNodeState(std::size_t i, const ShellVec3& position, const ShellVec3& normal, const ShellVec3& velocity);

  /// Node i's own critical time step (s), times the Courant factor: the estimate of
  /// stableTimeStep() with node i's spacing (the finest of its kernel's), thickness and step
  /// inertia; infinite for a clamped node. The classes of the multi-rate scheme come from it.
  double nodeStableStep(std::size_t i) const { return m_ownStep[i]; }
  /// Stress point i's own critical step (s), times the Courant factor: the shortest over the
  /// nodes its kernel reaches of its stiffness against their mass and rotary inertia.
  double pointStableStep(std::size_t i) const { return m_pointStep[i]; }

  /// One explicit central-difference step of size dt, every node and stress point at dt.
  void step(double dt);
  /// Advances the shell by the interval dt (s), to be in step with another solver at its end (the
  /// fluid, once per fluid step). Single rate (ShellParameters::subcycling false): K = ⌈dt /
  /// stableTimeStep()⌉ equal steps. Multi-rate: K fine steps, each stress point and hourglass pair
  /// evaluated every 2^c of them by its class (shell/step_classes.hpp). Returns K.
  long advanceInterval(double dt);
  /// The largest angular frequency (rad/s) of the shell linearised about its current state, with
  /// the elastic stiffness of its layers (an upper bound for one that yields or softens), from
  /// the force terms of the stress points with `pointTerm[j]` set and the hourglass pairs with a
  /// node that has `nodeTerm[i]` set: power iteration on M⁻¹K over the free nodes' five degrees
  /// of freedom (translation, director rotation), K applied by differences of the internal forces
  /// (shell/shell_spectrum.cpp). The state is left as it was.
  double maxFrequency(const std::vector<std::uint8_t>& pointTerm, const std::vector<std::uint8_t>& nodeTerm,
                      int iterations);
  /// The largest frequency (rad/s) of each group of terms the spectral step estimate measured
  /// (ShellParameters::StepEstimate::Spectral; finest group first, see measureOwnSteps), and how
  /// many times it has measured them; empty and 0 under the bound.
  const std::vector<double>& measuredFrequencies() const { return m_groupFrequency; }
  std::int64_t spectrumMeasurements() const { return m_spectrumMeasurements; }
  /// The classes of the last interval (all 0 after step() or a single-rate interval).
  const ShellStepClasses& stepClasses() const { return m_classes; }
  /// Stress-point evaluations so far (each point once per firing of its class): with
  /// nodes × fine steps, what the subcycling saved.
  std::uint64_t pointEvaluations() const { return m_pointEvaluations; }
  /// Wall-clock seconds so far in each pass of a step (docs/shell-and-damage.md, "Profile"):
  /// gradients and strains, the through-thickness layers (return mapping, damage, resultants),
  /// the forces (stress divergence, transverse shear, hourglass, pressure), the integrator, and
  /// fracture (cutting links and rebuilding the corrected gradients).
  /// spectrum: the spectral step estimate's measurements (maxFrequency).
  struct Timings { double gradients = 0, layers = 0, forces = 0, integration = 0, fracture = 0, spectrum = 0; };
  const Timings& timings() const { return m_timings; }
  /// `steps` steps of size dt; polls `cancel` every step (throws RunCancelled).
  void advance(int steps, double dt, const Cancellation& cancel);

  std::size_t size() const { return m_position.size(); }
  double time() const { return m_time; }
  const std::vector<ShellVec3>& positions() const { return m_position; }
  const std::vector<ShellVec3>& velocities() const { return m_velocity; }
  const std::vector<ShellVec3>& normals() const { return m_normal; }
  /// Angular velocities of the directors (rad/s), perpendicular to them.
  const std::vector<ShellVec3>& spins() const { return m_spin; }
  /// Rotary inertia of node i's director (kg m²).
  double rotaryInertia(std::size_t i) const { return m_inertia[i]; }
  /// Transverse displacement (z) of a node (m).
  double deflection(std::size_t i) const { return m_position[i][2]; }
  /// Largest accumulated plastic strain over the layers of a node.
  double maxPlasticStrain(std::size_t i) const;
  /// Number of the node's layers that have reached D_c (all of them once it has fractured).
  int failedLayers(std::size_t i) const;
  /// Largest damage over the layers of a node.
  double maxDamage(std::size_t i) const;
  bool fractured(std::size_t i) const { return m_fractured[i] != 0; }
  /// Translational mass of node i (kg): ρ t_i ω_i (0 for clamped nodes outside the plate).
  double mass(std::size_t i) const { return m_mass[i]; }
  /// Thickness t_i of node i (m): ShellNodes::thickness, or the uniform ShellParameters::thickness.
  double thickness(std::size_t i) const { return m_thickness[i]; }
  /// Bending moment per unit length at node i as of the last step, (M_11, M_22, M_12) in the
  /// reference axes (N m/m, Σ_k w_k ξ_k (1 − D_k) S_k); zero where i is not a stress point.
  const std::array<double, 3>& bendingMoment(std::size_t i) const { return m_moment[i]; }
  /// Clamped nodes keep their position: a contact on them loads the clamp, not the plate.
  bool clamped(std::size_t i) const { return m_clamped[i] != 0; }
  std::size_t fracturedCount() const;
  /// Sets the damage of every layer of node i to D_c and applies the fracture rule (tests, and
  /// pre-cracks given as a set of failed stress points).
  void fractureNode(std::size_t i);
  /// Time (s) at the start of the step in which node i fractured; NaN while it is intact.
  double fractureTime(std::size_t i) const { return m_fractureTime[i]; }
  /// The fractured nodes in the order they failed (the crack paths' history).
  const std::vector<std::size_t>& fractureOrder() const { return m_fractureOrder; }
  /// Pre-crack: cuts every link whose reference segment strictly crosses the segment [a, b] of
  /// the reference plane (m), then rebuilds the corrected gradients (free crack lips follow). Place
  /// a crack between node rows: a link that only touches the segment at a node is kept.
  void cutAlongSegment(const std::array<double, 2>& a, const std::array<double, 2>& b);
  /// cutAlongSegment for several segments (a polyline, a hole's edge) with one rebuild.
  void cutAlongSegments(const std::vector<std::array<std::array<double, 2>, 2>>& segments);
  /// Number of active links whose reference segment strictly crosses [a, b] (each pair once).
  std::size_t linksCrossing(const std::array<double, 2>& a, const std::array<double, 2>& b) const;
  /// Kinetic energy of translation and of the director rotation (J).
  double kineticEnergy() const;
  /// Elastic energy stored at the current positions (J): the layers' ½ σ:(E − Eᵖ) weighted by
  /// their (1 − D), the transverse shear's and the hourglass springs' (docs/shell-and-damage.md).
  double strainEnergy() const;

  /// Every per-node, per-layer and per-pair array and the clock (docs/checkpoints.md): cracks cut
  /// pairs and change the corrections, so even the geometric ones are state.
  void exchangeState(StateArchive& archive);

private:
  /// h_ij = (h/Δ) (Δ_i + Δ_j)/2: symmetric, so j sees i whenever i sees j (a refined node set's
  /// kernels grade with its spacing; the corrected gradients stay first-order consistent).
  double pairSmoothingLength(std::size_t i, std::size_t j) const {
    return m_params.smoothingRatio * (0.5 * (m_nodeSpacing[i] + m_nodeSpacing[j]));
  }
  void buildNeighbours();
  void buildCorrections();
  /// buildCorrections for `nodes` only (sorted, unique) and the back coefficients of their links.
  void buildCorrections(const std::vector<std::size_t>& nodes);
  void correctNode(std::size_t i);
  void linkBackCoefficients(std::size_t i);
  /// The forces of the terms whose class is at most `firing` (all of them in the single rate),
  /// each weighted by its 2^c: the impulse of its interval over the fine step dt.
  void computeForces(double dt, int firing);
  void fineStep(double dt, int firing);
  void computeOwnSteps();
  void measureOwnSteps();
  /// A_α and G_α of node i at the current positions and directors (the identity and zero for a
  /// node without a gradient).
  void currentGradients(std::size_t i, std::array<double, 6>& A, std::array<double, 6>& G) const;
  void computePairHourglass();
  /// Cuts the links of fractured node i and those crossing its cell; returns the cut links' ends.
  std::vector<std::size_t> cutLinksOf(std::size_t i);
  void rebuildAfterCuts();
  /// rebuildAfterCuts after cuts whose links' ends are `touched`.
  void rebuildAfterCuts(std::vector<std::size_t> touched);
  /// Cuts every link of a node without a gradient; returns the cut links' ends.
  std::vector<std::size_t> cutFragmentLinks();

  ShellParameters m_params;
  ThroughThicknessRule m_rule;
  int m_layersToFracture = 1;  ///< failed layers that fracture a stress point
  double m_spacing = 0.0;
  double m_pressure = 0.0;
  double m_time = 0.0;
  double m_stableStep = 0.0;

  // Per node (structure of arrays).
  std::vector<std::array<double, 2>> m_reference;
  std::vector<double> m_volume, m_area, m_mass, m_inertia, m_thickness, m_nodeSpacing;
  std::vector<std::uint8_t> m_clamped, m_fractured, m_hasGradient;
  std::vector<double> m_fractureTime;
  std::vector<std::size_t> m_fractureOrder;
  std::vector<ShellVec3> m_position, m_velocity, m_normal, m_spin, m_force, m_directorForce, m_external;
  std::vector<std::array<double, 6>> m_gradX, m_gradN;  ///< A_α, G_α (α-major: a0,a1,a2, b0,b1,b2)
  std::vector<std::array<double, 6>> m_stressP, m_stressR;  ///< conjugates of A_α and G_α
  std::vector<std::array<double, 2>> m_shearQ;              ///< ω_i Q_i (transverse shear)
  std::vector<std::array<double, 3>> m_moment;              ///< M per unit length (output only)
  std::vector<std::array<double, 3>> m_hourglass;           ///< k_x, k_n, k_s of the node's thickness

  std::vector<std::array<double, 8>> m_pointStrain;        ///< ε (3), κ (3), γ (2) of the last pass
  std::vector<double> m_ownStep, m_pointStep;               ///< nodeStableStep, pointStableStep
  std::vector<std::uint8_t> m_newlyFractured;
  ShellStepClasses m_classes;
  std::uint64_t m_pointEvaluations = 0;
  Timings m_timings;
  bool m_elasticProbe = false;  ///< computeForces for maxFrequency: elastic layers, no state changes
  // The spectral step estimate: the bound's own steps (which group the terms), the frequency
  // measured for each group, and the nodes whose gradients were rebuilt since it was measured.
  std::vector<double> m_boundPointStep;
  double m_boundStableStep = 0.0;
  std::vector<double> m_groupFrequency;
  std::size_t m_rebuiltSinceMeasure = 0;
  std::int64_t m_spectrumMeasurements = 0;

  // Per node and layer (node-major, m_rule.xi.size() layers).
  std::vector<std::array<double, 3>> m_plasticStrainTensor;
  std::vector<double> m_plasticStrain;
  std::vector<TransverseShear> m_plasticShear;  ///< per layer: transverse plastic tensor shears ε^p_13, ε^p_23
  std::vector<DamageState> m_damage;

  // Pairs in CSR order (i's neighbours j), both directions stored.
  std::vector<std::size_t> m_offset, m_neighbour, m_reverse;
  std::size_t m_maxPairs = 0;  ///< the most pairs of one node (the pair loops' scratch)
  std::vector<std::uint8_t> m_active;
  std::vector<std::array<double, 2>> m_separation;  ///< X_j − X_i
  std::vector<std::array<double, 2>> m_coeff;       ///< V_j B_ij
  std::vector<std::array<double, 2>> m_coeffBack;   ///< V_i B_ji
  std::vector<std::array<double, 2>> m_shearCoeff;  ///< T_i⁻¹ V_j W_ij X_ij
  std::vector<std::array<double, 2>> m_shearBack;   ///< T_j⁻¹ V_i W_ij X_ji
  std::vector<double> m_kernel;                     ///< W(|X_ij|)
  /// The pair's hourglass stiffnesses times hw = W_ij V_i V_j / |X_ij|² (its thinner node's k_x,
  /// k_n, k_s): constant, derived from the reference (pairHourglassStiffness).
  std::vector<std::array<double, 3>> m_pairHourglass;
};

}  // namespace rupture
