// SPH results with SI units, labels and descriptions (see rupture/result_fields.hpp).
// Adding a scalar: one line in the scenario's list (or in commonSummary for every fluid run).
#include "scenarios/fluid/fluid_results.hpp"

namespace rupture {
namespace {

/// The scalars finishFluidRun adds to every SPH run's summary.
ResultFields commonSummary() {
  return {
      {"completed", "1", "Completed", "1 when the run reached end_time, 0 when cancelled"},
      {"stop_reason", "", "Stop reason", "Why the run stopped"},
      {"mass_error", "1", "Mass error", "Relative change of the fluid mass over the run"},
      {"max_density_error", "1", "Max density error", "Largest |rho/rho0 - 1| over fluid particles and outputs"},
      {"particles_outside_max", "1", "Particles outside", "Most fluid particles found outside the domain at an output"},
      {"final_time", "s", "Final time", "Simulated time when the run stopped"},
      {"steps", "1", "Steps", "Time steps taken"},
      {"time_step_min", "s", "Min time step", "Smallest adaptive time step"},
      {"time_step_max", "s", "Max time step", "Largest adaptive time step"},
      {"particles", "1", "Particles", "Fluid and wall particles"},
      {"fluid_particles", "1", "Fluid particles", "Fluid particles"},
      {"sound_speed", "m/s", "Sound speed", "Numerical speed of sound c0 of the weakly compressible fluid"},
      {"smoothing_length", "m", "Smoothing length", "Kernel smoothing length h"},
      {"neighbour_list_builds", "1", "Neighbour-list builds", "Cell-list rebuilds over the run"},
      {"wall_time_s", "s", "Wall time", "Wall-clock time of the run"},
  };
}


const ResultField kProbePressure = {"probe_pressure_*", "Pa", "Probe pressure",
                                    "Kernel-averaged pressure at probe k (its position in the dataset's \"position\" attribute)"};

}  // namespace

std::vector<std::pair<std::string, std::string>> seriesColumns(const ResultFields& series, int dimension) {
  std::vector<std::pair<std::string, std::string>> columns;
  for (const ResultField& f : series)
    if (f.name.back() != '*') columns.emplace_back(f.name, f.unitFor(dimension));
  return columns;
}

ResultFields withFluidCommonSummary(ResultFields own) {
  for (ResultField& f : commonSummary()) own.push_back(std::move(f));
  return own;
}

const ResultFields& damBreakSummaryFields() {
  static const ResultFields fields = withFluidCommonSummary({
      {"front_position_final", "m", "Final front position", "x of the leading fluid particle's edge at the end"},
      {"peak_pressure", "Pa", "Peak probe pressure", "Largest pressure at any probe (null without probes)"},
      {"kinetic_energy_final", "J", "Final kinetic energy", "Kinetic energy of the fluid at the end", "J/m"},
      {"potential_energy_initial", "J", "Initial potential energy", "Gravitational potential energy at the start", "J/m"},
      {"potential_energy_final", "J", "Final potential energy", "Gravitational potential energy at the end", "J/m"},
  });
  return fields;
}

const ResultFields& damBreakSeriesFields() {
  static const ResultFields fields = {
      {"time", "s", "Time", "Simulated time"},
      {"front_position", "m", "Front position", "x of the leading fluid particle's edge"},
      {"fluid_mass", "kg", "Fluid mass", "Total fluid mass", "kg/m"},
      {"kinetic_energy", "J", "Kinetic energy", "Kinetic energy of the fluid", "J/m"},
      {"potential_energy", "J", "Potential energy", "Gravitational potential energy of the fluid", "J/m"},
      {"max_density_error", "1", "Max density error", "Largest |rho/rho0 - 1| over fluid particles"},
      {"particles_outside", "1", "Particles outside", "Fluid particles outside the domain"},
      {"time_step", "s", "Time step", "Adaptive time step of the last step"},
      kProbePressure,
  };
  return fields;
}

const ResultFields& pistonColumnSummaryFields() {
  static const ResultFields fields = withFluidCommonSummary({
      {"peak_pressure", "Pa", "Peak probe pressure", "Largest pressure at any probe (null without probes)"},
      {"peak_bottom_pressure", "Pa", "Peak bottom pressure", "Largest mean pressure on the column's bottom"},
      {"first_peak_bottom_pressure", "Pa", "First bottom-pressure peak", "Largest bottom pressure within the first wave transit"},
      {"time_of_first_peak", "s", "Time of first peak", "Time of the first bottom-pressure peak"},
      {"acoustic_pressure", "Pa", "Acoustic pressure", "rho0 c0 v0: the linear-acoustics pressure of the piston impact (v0 the carriage's speed with an impactor)"},
      {"shock_pressure", "Pa", "Shock pressure", "Pressure behind the shock from the Rankine-Hugoniot relations of the EOS"},
      {"piston_initial_speed", "m/s", "Piston initial speed", "Speed of the piston at the start"},
      {"piston_final_speed", "m/s", "Piston final speed", "Speed of the piston (its wetted face) at the end"},
      {"max_piston_speed", "m/s", "Max piston speed", "Largest speed of the piston (its wetted face) into the column"},
      {"impactor_model", "", "Impactor model", "two_body or elastic_piston when a carriage strikes the piston (null without impactor)"},
      {"carriage_final_speed", "m/s", "Carriage final speed", "Speed of the carriage at the end (null without impactor)"},
      {"piston_final_position", "m", "Piston final position", "Piston displacement at the end"},
      {"piston_impulse", "N s", "Piston impulse", "Impulse of the fluid's force on the piston", "N s/m"},
      {"piston_mass", "kg", "Piston mass", "Mass of a free piston (null for an imposed motion)", "kg/m"},
      {"section_area", "m^2", "Section area", "Column cross-section (a width in 2-D)", "m"},
  });
  return fields;
}

const ResultFields& pistonColumnSeriesFields() {
  static const ResultFields fields = {
      {"time", "s", "Time", "Simulated time"},
      {"bottom_pressure", "Pa", "Bottom pressure", "Mean pressure on the column's bottom"},
      {"piston_position", "m", "Piston position", "Piston displacement"},
      {"piston_velocity", "m/s", "Piston velocity", "Piston velocity along its axis"},
      {"piston_force", "N", "Piston force", "Fluid's force on the piston, positive when it pushes the piston back", "N/m"},
      {"fluid_mass", "kg", "Fluid mass", "Total fluid mass", "kg/m"},
      {"kinetic_energy", "J", "Kinetic energy", "Kinetic energy of the fluid", "J/m"},
      {"max_density_error", "1", "Max density error", "Largest |rho/rho0 - 1| over fluid particles"},
      {"particles_outside", "1", "Particles outside", "Fluid particles outside the column"},
      {"time_step", "s", "Time step", "Adaptive time step of the last step"},
      kProbePressure,
  };
  return fields;
}

}  // namespace rupture
