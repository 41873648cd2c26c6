// What an impact run reports: /summary scalars and /series columns, with SI units, labels and
// descriptions (see rupture/result_fields.hpp). Adding a scalar: one line here.
#include "scenarios/impact/impact_results.hpp"

namespace rupture {

const ResultFields& impactSummaryFields() {
  static const ResultFields fields = {
      {"crack_speed_max", "m/s", "Max crack speed",
       "Largest speed of the crack connected to its origin over the run, jumps (zones that cracked apart joining it) excluded"},
      {"crack_length", "m", "Crack length", "Distance of the farthest damaged point from the impact point"},
      {"crack_jumps", "1", "Crack jumps",
       "Times the crack tip jumped ahead by joining a zone that cracked apart from it (faster than twice sqrt(E/rho))"},
      {"crack_jumped_length", "m", "Jumped length", "Crack length gained by those jumps, not by propagation"},
      {"crack_angle", "rad", "Crack angle",
       "Direction of the crack tip from the first notch's end, from the notch's direction (2D: counter-clockwise positive; null without a notch or a crack)"},
      {"branches", "1", "Crack branches", "Crack branches counted on a ring around the impact point"},
      {"fragments", "1", "Fragments", "Connected groups of elements through intact bonds at the end"},
      {"broken_bonds", "1", "Broken bonds", "Bonds broken at the end of the run"},
      {"broken_bond_fraction", "1", "Broken-bond fraction", "Broken bonds / initial bonds at the end of the run"},
      {"final_time", "s", "Final time", "Simulated time when the run stopped"},
      {"steps", "1", "Steps", "Time steps taken"},
      {"time_step", "s", "Time step", "Time step used"},
      {"critical_time_step", "s", "Critical time step", "Stability limit of the explicit scheme for this sample"},
      {"elements", "1", "Elements", "Discrete elements in the sample"},
      {"bonds", "1", "Bonds", "Bonds in the sample before impact"},
      {"wall_time_s", "s", "Wall time", "Wall-clock time of the run"},
      {"completed", "1", "Completed", "1 when the run reached end_time, 0 when cancelled"},
      {"stop_reason", "", "Stop reason", "Why the run stopped"},
      {"projectile_final_speed", "m/s", "Projectile final speed", "Speed of the rigid projectile at the end (null without one)"},
      {"kinetic_energy", "J", "Final kinetic energy", "Kinetic energy of the sample at the end"},
      {"elastic_energy", "J", "Final elastic energy", "Elastic energy in intact bonds at the end"},
  };
  return fields;
}

const ResultFields& impactSeriesFields() {
  static const ResultFields fields = {
      {"time", "s", "Time", "Simulated time"},
      {"crack_tip_x", "m", "Crack tip x", "x of the crack tip (farthest damaged point)"},
      {"crack_tip_y", "m", "Crack tip y", "y of the crack tip"},
      {"crack_tip_z", "m", "Crack tip z", "z of the crack tip"},
      {"crack_length", "m", "Crack length", "Distance of the crack tip from the impact point"},
      {"crack_speed", "m/s", "Crack speed", "Crack-tip speed, jumps excluded (smoothed over 5 rows)"},
      {"crack_jump", "m", "Crack jump", "Length the tip gained at once at this row by joining a zone that cracked apart (0 otherwise)"},
      {"crack_angle", "rad", "Crack angle", "Direction of the crack tip from the first notch's end, from the notch's direction (2D: counter-clockwise positive)"},
      {"kinetic_energy", "J", "Kinetic energy", "Kinetic energy of the sample"},
      {"elastic_energy", "J", "Elastic energy", "Elastic energy in intact bonds"},
      {"projectile_kinetic_energy", "J", "Projectile kinetic energy", "Kinetic energy of the projectile"},
      {"broken_bond_fraction", "1", "Broken-bond fraction", "Broken bonds / initial bonds"},
  };
  return fields;
}

}  // namespace rupture
