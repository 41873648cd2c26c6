// What a dynamic-tension run reports: its /summary scalars and /series columns, with SI units,
// labels and descriptions (the one source every writer and reader uses; see rupture/result_fields.hpp).
// Adding a scalar: one line here, and the value in the run's summary.
#include "scenarios/dynamic_tension/dynamic_tension_results.hpp"

namespace rupture {

const ResultFields& dynamicTensionSummaryFields() {
  static const ResultFields fields = {
      {"peak_stress", "Pa", "Peak stress", "Maximum of the mean boundary stress (X_min and X_max faces) over the run"},
      {"strain_at_peak", "1", "Strain at peak", "Nominal strain (face displacement / gauge length) at the peak stress"},
      {"time_at_peak", "s", "Time at peak", "Simulated time at the peak stress"},
      {"stress_xmin_at_peak", "Pa", "X_min stress at peak", "Boundary stress on the fixed X_min face at the peak"},
      {"stress_xmax_at_peak", "Pa", "X_max stress at peak", "Boundary stress on the pulled X_max face at the peak"},
      {"max_stress_xmin", "Pa", "Max X_min stress", "Largest boundary stress on the X_min face over the run"},
      {"max_stress_xmax", "Pa", "Max X_max stress", "Largest boundary stress on the X_max face over the run"},
      {"equilibrium_ratio", "1", "Equilibrium ratio", "Loading branch: sum of |stress X_max - stress X_min| / sum of mean stress over the steps from 1/4 of the strain at peak to the peak (0: quasi-static equilibrium)"},
      {"equilibrium_ratio_at_peak", "1", "Equilibrium ratio at peak", "|stress X_min - stress X_max| / peak stress at the peak step alone"},
      {"crack_onset_strain", "1", "Crack-onset strain", "Nominal strain when the first bond broke"},
      {"crack_onset_time", "s", "Crack-onset time", "Simulated time when the first bond broke"},
      {"strain_rate_at_onset", "1/s", "Strain rate at onset", "Imposed strain rate when the first bond broke (below strain_rate while a ramp is rising)"},
      {"broken_bond_fraction", "1", "Broken-bond fraction", "Broken bonds / initial bonds at the end of the run"},
      {"broken_bonds", "1", "Broken bonds", "Number of bonds broken at the end of the run"},
      {"fragments", "1", "Fragments", "Macroscopic fragments at the end: groups of elements joined by intact bonds with at least output.fragment_min_fraction of the elements (and 2)"},
      {"debris", "1", "Debris", "Smaller groups of elements (single elements included) at the end"},
      {"largest_fragment_fraction", "1", "Largest fragment fraction", "Elements in the largest macroscopic fragment / all elements (0 when none)"},
      {"cracks_crossing", "1", "Cracks crossing", "Cracks crossing the section: median over lines along x of the distinct pieces met minus 1"},
      {"separated", "1", "Separated", "1 when no path of intact bonds joins the two loaded faces any more"},
      {"separation_strain", "1", "Separation strain", "Nominal strain when the loaded faces were first separated"},
      {"separation_time", "s", "Separation time", "Simulated time when the loaded faces were first separated"},
      {"final_strain", "1", "Final strain", "Nominal strain when the run stopped"},
      {"final_time", "s", "Final time", "Simulated time when the run stopped"},
      {"steps", "1", "Steps", "Time steps taken"},
      {"time_step", "s", "Time step", "Time step used"},
      {"critical_time_step", "s", "Critical time step", "Stability limit of the explicit scheme for this sample"},
      {"wall_time_s", "s", "Wall time", "Wall-clock time of the run"},
      {"completed", "1", "Completed", "1 when the run reached its stop rule, 0 when cancelled"},
      {"stop_reason", "", "Stop reason", "Why the run stopped: separated, unloaded, post_peak_drop, max_strain, max_steps or cancelled"},
      {"elements", "1", "Elements", "Discrete elements in the sample"},
      {"bonds", "1", "Bonds", "Bonds in the sample before loading"},
      {"mean_coordination", "1", "Mean coordination", "Mean number of bonds per element"},
      {"porosity", "1", "Porosity", "Void fraction of the sample"},
      {"strain_rate", "1/s", "Strain rate", "Imposed nominal strain rate (face velocity / gauge length)"},
      {"initial_velocity", "", "Initial velocity field", "V0 (at rest), VL (linear) or VH (from the preliminary run)"},
      {"max_velocity", "m/s", "Face velocity", "Imposed X_max face velocity after the ramp"},
      {"ramp_time", "s", "Ramp time", "Duration of the sinusoidal rise of the face velocity"},
      {"wave_speed", "m/s", "Wave speed", "Longitudinal wave speed sqrt(E/rho) of the bonded material"},
      {"gauge_length", "m", "Gauge length", "Sample length between the loaded faces"},
      {"section", "m^2", "Cross-section", "Sample cross-section normal to x"},
      {"modulus", "Pa", "Modulus", "Young's modulus used for the wave speed"},
      {"sample_from_cache", "1", "Sample from cache", "1 when the bonded sample was loaded from the sample cache, 0 when built"},
  };
  return fields;
}

const ResultFields& dynamicTensionSeriesFields() {
  static const ResultFields fields = {
      {"time", "s", "Time", "Simulated time"},
      {"strain", "1", "Strain", "Nominal strain (face displacement / gauge length)"},
      {"stress_xmin", "Pa", "X_min stress", "Boundary stress on the fixed X_min face"},
      {"stress_xmax", "Pa", "X_max stress", "Boundary stress on the pulled X_max face"},
      {"stress_mean", "Pa", "Mean stress", "Mean of the two boundary stresses"},
      {"broken_bond_fraction", "1", "Broken-bond fraction", "Broken bonds / initial bonds"},
      {"kinetic_energy", "J", "Kinetic energy", "Kinetic energy of all elements"},
      {"elastic_energy", "J", "Elastic energy", "Elastic energy stored in intact bonds"},
      {"face_velocity", "m/s", "Face velocity", "Imposed x-velocity of the X_max face"},
  };
  return fields;
}

}  // namespace rupture
