#include "shell/shell_parameters.hpp"

#include <cmath>

#include "core/format_number.hpp"
#include "rupture/spec_error.hpp"

namespace rupture {
namespace {

void requirePositive(double v, const std::string& field, const char* unit) {
  if (!(std::isfinite(v) && v > 0.0)) throw SpecError(field, formatNumber(v), std::string("a value > 0 (") + unit + ")");
}
}  // namespace

void validateShellParameters(const ShellParameters& p, const std::string& prefix) {
  requirePositive(p.thickness, prefix + ".thickness", "m");
  requirePositive(p.density, prefix + ".density", "kg/m^3");
  validateElasticPlastic(p.material, prefix + ".material");
  if (p.damage) validateDamage(p.damageLaw, prefix + ".damage");
  if (p.thicknessPoints < 2 || p.thicknessPoints > 7)
    throw SpecError(prefix + ".thickness_points", std::to_string(p.thicknessPoints), "an integer in [2, 7]");
  if (!(p.fractureLayerFraction > 0.0 && p.fractureLayerFraction <= 1.0))
    throw SpecError(prefix + ".fracture_layer_fraction", formatNumber(p.fractureLayerFraction),
                    "a fraction of the layers in (0, 1]");
  if (!(p.shearCorrection > 0.0 && p.shearCorrection <= 1.0))
    throw SpecError(prefix + ".shear_correction", formatNumber(p.shearCorrection), "a number in (0, 1]");
  if (!(p.smoothingRatio >= 1.0 && p.smoothingRatio <= 2.5))
    throw SpecError(prefix + ".smoothing_ratio", formatNumber(p.smoothingRatio), "a number in [1, 2.5] (h over spacing)");
  if (!(p.hourglassCoefficient >= 0.0 && p.hourglassCoefficient <= 1.0))
    throw SpecError(prefix + ".hourglass_coefficient", formatNumber(p.hourglassCoefficient), "a number in [0, 1]");
  if (!(std::isfinite(p.rotaryInertiaScale) && p.rotaryInertiaScale >= 1.0))
    throw SpecError(prefix + ".rotary_inertia_scale", formatNumber(p.rotaryInertiaScale), "a number >= 1");
  if (!(std::isfinite(p.stepRotaryInertia) && p.stepRotaryInertia > 0.0))
    throw SpecError(prefix + ".step_rotary_inertia", formatNumber(p.stepRotaryInertia),
                    "a number > 0 (the rotary inertia beside a thickness step in units of rho t_i t_j^2/12)");
  if (!(std::isfinite(p.dampingRate) && p.dampingRate >= 0.0))
    throw SpecError(prefix + ".damping_rate", formatNumber(p.dampingRate), "a rate >= 0 (1/s)");
  if (!(p.courantFactor > 0.0 && p.courantFactor <= 1.0))
    throw SpecError(prefix + ".courant_factor", formatNumber(p.courantFactor), "a number in (0, 1]");
}

}  // namespace rupture
