// tank-impact results with SI units, labels and descriptions (see rupture/result_fields.hpp).
#include "scenarios/tank_impact/tank_impact_results.hpp"

#include "scenarios/fluid/fluid_results.hpp"

namespace rupture {

const ResultFields& tankImpactSummaryFields() {
  static const ResultFields fields = withFluidCommonSummary({
      {"first_pressure_peak", "Pa", "First pressure peak", "Largest gauge pressure within the first wave transit (t <= 2.5 H/c0)"},
      {"time_of_first_peak", "s", "Time of first peak", "Time of the first gauge-pressure peak"},
      {"peak_gauge_pressure", "Pa", "Peak gauge pressure", "Largest gauge pressure over the run"},
      {"peak_pressure", "Pa", "Peak probe pressure", "Largest pressure at any further probe (null without probes)"},
      {"acoustic_pressure", "Pa", "Acoustic pressure", "rho0 c0 V: the linear-acoustics pressure of the impact"},
      {"max_jet_speed", "m/s", "Max jet speed", "Largest mean axial (downward) speed of the water below the plate (null if none went through)"},
      {"final_jet_speed", "m/s", "Final jet speed", "Mean axial speed of the water below the plate at the end (null if none)"},
      {"jet_front_speed", "m/s", "Jet front speed", "Mean axial speed of the jet's front at the end: the water within one smoothing length of the lowest water below the plate, what a film tracks (null if none)"},
      {"final_outflow_speed", "m/s", "Final outflow speed", "Mean axial speed at the end of the water within one smoothing length below the plate's face: the speed at which the flow leaves it (null if none below)"},
      {"mean_outflow_speed", "m/s", "Mean outflow speed", "The outflow speed averaged over the output rows of the run's second half that have water leaving the plate: the steady jet, past the first burst (null if none)"},
      {"max_deflection", "m", "Max deflection", "Largest downward deflection of the plate at (D + d)/4 from the centre"},
      {"deflection_radius", "m", "Deflection radius", "(D + d)/4: where the deflection is read (d: hole diameter, 0 without)"},
      {"final_tongue_angle", "rad", "Final tongue angle", "Opening angle of the U tongue at the end: its inclination to the plate's plane, the hinge's sinking removed (null for other pre-cracks)"},
      {"time_to_fracture", "s", "Time to fracture", "First fracture of a stress point beyond the pre-cracks (null if none)"},
      {"fracture_radius", "m", "Fracture radius", "Distance from the axis of the first stress point the impact fractured (null if none): the spot face's rim is D/2"},
      {"cracked_length", "m", "Cracked length", "Length of the cracks the impact opened beyond the pre-cracks, at the end"},
      {"rim_torn_fraction", "1", "Rim torn fraction", "Fraction of the spot face's rim circumference along which the plate has torn at the end: the angular cover of the fractured cells within two plate spacings of r = D/2 (1: the seed's rupture along the rim)"},
      {"fractured_nodes", "1", "Fractured nodes", "Plate nodes fractured by the impact at the end"},
      {"fluid_below_final", "1", "Fluid below the plate", "Fluid particles below the plate at the end"},
      {"carriage_initial_speed", "m/s", "Carriage initial speed", "V"},
      {"carriage_final_speed", "m/s", "Carriage final speed", "Speed of the carriage at the end (of carriage and piston with the rigid impactor)"},
      {"carriage_final_displacement", "m", "Carriage final displacement", "Displacement of the carriage at the end (downwards)"},
      {"carriage_mass", "kg", "Carriage mass", "M"},
      {"impactor_model", "", "Impactor model", "rigid (carriage and piston one body), two_body (rigid piston) or elastic_piston"},
      {"piston_mass", "kg", "Piston mass", "Mass of the piston as a body of its own (null with the rigid impactor)"},
      {"max_piston_face_speed", "m/s", "Max piston face speed", "Largest downward speed of the piston's wetted face"},
      {"piston_final_speed", "m/s", "Piston final speed", "Mean speed of the piston at the end (null with the rigid impactor)"},
      {"plate_nodes", "1", "Plate nodes", "Nodes of the SPH shell (hole nodes excluded)"},
      {"shell_steps", "1", "Shell steps", "Shell time steps, sub-cycled inside the fluid steps (with plate.subcycling, the fine steps: the finest class's)"},
      {"fluid_time_s", "s", "Fluid wall time", "Wall-clock time of the fluid's steps"},
      {"shell_time_s", "s", "Shell wall time", "Wall-clock time of the shell's sub-cycles"},
      {"contact_time_s", "s", "Contact wall time", "Wall-clock time of the fluid-shell contact"},
      {"shell_point_evaluations", "1", "Shell point evaluations", "Stress-point evaluations of the shell (gradients, layers, resultants): nodes times shell steps in the single rate, fewer with plate.subcycling"},
      {"shell_coarsest_class", "1", "Shell coarsest class", "The coarsest time-step class of the shell's last fluid step: its points are evaluated every 2^c shell steps (0: single rate)"},
      {"shell_points_per_class", "", "Shell points per class", "Stress points in each time-step class at the last fluid step, as 'class: count' pairs"},
      {"shell_gradients_time_s", "s", "Shell gradients wall time", "Wall-clock time of the shell's gradients and strains"},
      {"shell_layers_time_s", "s", "Shell layers wall time", "Wall-clock time of the shell's layers through the thickness (return mapping, damage, resultants)"},
      {"shell_forces_time_s", "s", "Shell forces wall time", "Wall-clock time of the shell's nodal forces (stress divergence, transverse shear, hourglass, pressure)"},
      {"shell_integration_time_s", "s", "Shell integration wall time", "Wall-clock time of the shell's time integration (velocities, positions, directors)"},
      {"shell_fracture_time_s", "s", "Shell fracture wall time", "Wall-clock time of the shell's fracture handling (cutting links, rebuilding the corrected gradients)"},
      {"shell_spectrum_time_s", "s", "Shell spectrum wall time", "Wall-clock time of the spectral step estimate's measurements (plate.step_estimate spectral; 0 under the bound)"},
      {"shell_spectrum_measurements", "1", "Shell spectrum measurements", "How many times the spectral step estimate measured the shell's largest frequencies (0 under the bound)"},
      {"shell_max_frequency", "rad/s", "Shell max frequency", "The largest frequency of the shell's linearised elastic operator at the last measurement, which sets its finest step (null under the bound)"},
      {"contact_method", "", "Contact method", "Fluid-structure contact: pinball or master_slave"},
      {"specimen", "", "Specimen", "The seed's specimen (Table 4) the spec names (null: none)"},
      {"seed_first_peak_low", "Pa", "Seed: first peak, low", "Lowest first pressure peak the seed measured on this specimen (null: not given)"},
      {"seed_first_peak_high", "Pa", "Seed: first peak, high", "Highest first pressure peak the seed measured on this specimen (null: not given)"},
      {"seed_jet_speed", "m/s", "Seed: jet speed", "Jet speed the seed estimated from its film (null: not given)"},
      {"seed_simulated_jet_speed", "m/s", "Seed: simulated jet speed", "Jet speed of the seed's own simulation (null: not given)"},
      {"seed_tongue_angle", "rad", "Seed: tongue angle", "Opening of the U tongue the seed measured (null: not given)"},
      {"seed_time_to_fracture", "s", "Seed: time to fracture", "Time to fracture the seed measured (null: not given)"},
      {"seed_outcome", "", "Seed: outcome", "The specimen's final state in the seed's test (null: no specimen)"},
  });
  return fields;
}

const ResultFields& tankImpactSeriesFields() {
  static const ResultFields fields = {
      {"time", "s", "Time", "Simulated time"},
      {"gauge_pressure", "Pa", "Gauge pressure", "Kernel-averaged water pressure at the gauge"},
      {"carriage_displacement", "m", "Carriage displacement", "Displacement of the carriage (downwards)"},
      {"carriage_speed", "m/s", "Carriage speed", "Speed of the carriage (downwards)"},
      {"piston_face_speed", "m/s", "Piston face speed", "Downward speed of the piston's wetted face (the carriage's with the rigid impactor)"},
      {"contact_force", "N", "Contact force", "Carriage-piston contact force (0 with the rigid impactor: one body)"},
      {"jet_speed", "m/s", "Jet speed", "Mean axial (downward) speed of the water below the plate (0 if none)"},
      {"jet_front_speed", "m/s", "Jet front speed", "Mean axial speed of the water within one smoothing length of the lowest water below the plate (0 if none)"},
      {"outflow_speed", "m/s", "Outflow speed", "Mean axial speed of the water within one smoothing length below the plate's face (0 if none)"},
      {"deflection", "m", "Deflection", "Downward deflection of the plate at (D + d)/4 from the centre"},
      {"tongue_angle", "rad", "Tongue angle", "Opening angle of the U tongue: its inclination to the plate's plane, the hinge's sinking removed (0 for other pre-cracks)"},
      {"cracked_length", "m", "Cracked length", "Length of the cracks the impact opened beyond the pre-cracks"},
      {"fluid_below", "1", "Fluid below the plate", "Fluid particles below the plate"},
      {"plate_force", "N", "Plate force", "Downward force of the water on the plate (contact), clamp included"},
      {"fluid_mass", "kg", "Fluid mass", "Total fluid mass"},
      {"max_density_error", "1", "Max density error", "Largest |rho/rho0 - 1| over fluid particles"},
      {"time_step", "s", "Time step", "Fluid time step of the last step"},
      {"probe_pressure_*", "Pa", "Probe pressure",
       "Kernel-averaged pressure at probe k (its position in the dataset's \"position\" attribute)"},
  };
  return fields;
}

}  // namespace rupture
