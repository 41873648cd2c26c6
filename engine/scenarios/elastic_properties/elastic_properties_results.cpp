// What an elastic-properties run reports in /summary, with SI units, labels and descriptions
// (see rupture/result_fields.hpp). It writes no /series. Adding a scalar: one line here.
#include "scenarios/elastic_properties/elastic_properties_results.hpp"

namespace rupture {

const ResultFields& elasticPropertiesSummaryFields() {
  static const ResultFields fields = {
      {"young_modulus", "Pa", "Young's modulus", "Apparent Young's modulus from a quasi-static uniaxial strain"},
      {"poisson_ratio", "1", "Poisson's ratio", "Apparent Poisson's ratio from the lateral contraction"},
      {"converged", "1", "Converged", "1 when the static relaxation reached its tolerance"},
      {"relaxation_steps", "1", "Relaxation steps", "Damped steps of the static relaxation"},
      {"steps", "1", "Steps", "Relaxation steps of all the run's tension tests (a checkpoint's step counts them)"},
      {"elements", "1", "Elements", "Discrete elements in the sample"},
      {"bonds", "1", "Bonds", "Bonds in the sample"},
      {"mean_coordination", "1", "Mean coordination", "Mean number of bonds per element"},
      {"porosity", "1", "Porosity", "Void fraction of the sample"},
      {"wall_time_s", "s", "Wall time", "Wall-clock time of the run"},
      {"completed", "1", "Completed", "1 when the run finished, 0 when cancelled"},
      {"beam_young_modulus", "Pa", "Beam Young's modulus", "Calibrated microscopic beam modulus (calibration only)"},
      {"beam_radius_ratio", "1", "Beam radius ratio", "Calibrated beam radius / element radius (calibration only)"},
      {"target_young_modulus", "Pa", "Target Young's modulus", "Macroscopic modulus the calibration aims at"},
      {"target_poisson_ratio", "1", "Target Poisson's ratio", "Macroscopic Poisson's ratio the calibration aims at"},
      {"evaluations", "1", "Evaluations", "Samples measured by the calibration"},
      {"tensile_strength", "Pa", "Tensile strength", "Peak mean face stress of a damped quasi-static strain-step test to failure (beams)"},
      {"crack_onset_strain", "1", "Crack-onset strain", "Nominal strain when the first bond broke in the strength test (beams)"},
      {"strain_at_peak", "1", "Strain at peak", "Nominal strain at the tensile strength (beams)"},
      {"beam_failure_stress", "Pa", "Beam failure stress", "Calibrated beam failure stress (strength calibration only)"},
      {"target_tensile_strength", "Pa", "Target tensile strength", "Tensile strength the strength calibration aims at"},
      {"strength_evaluations", "1", "Strength evaluations", "Strength tests run by the strength calibration"},
  };
  return fields;
}

}  // namespace rupture
