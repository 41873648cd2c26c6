#include "plasticity/isotropic_hardening.hpp"

#include <cmath>

#include "core/format_number.hpp"
#include "rupture/spec_error.hpp"

namespace rupture {
void validateHardening(const IsotropicHardening& h, const std::string& prefix) {
  if (!(std::isfinite(h.initialYieldStress) && h.initialYieldStress > 0.0))
    throw SpecError(prefix + ".initial_yield_stress", formatNumber(h.initialYieldStress), "a stress > 0 (Pa)");
  if (!(std::isfinite(h.modulus) && h.modulus >= 0.0))
    throw SpecError(prefix + ".hardening_modulus", formatNumber(h.modulus), "a stress >= 0 (Pa)");
  if (h.kind == HardeningKind::johnsonCook && !(h.exponent > 0.0 && h.exponent <= 1.0))
    throw SpecError(prefix + ".hardening_exponent", formatNumber(h.exponent), "a number in (0, 1]");
}

HardeningKind hardeningKindFromName(const std::string& name, const std::string& field) {
  if (name == "linear") return HardeningKind::linear;
  if (name == "johnson_cook") return HardeningKind::johnsonCook;
  throw SpecError(field, "\"" + name + "\"", "\"linear\" or \"johnson_cook\"");
}

const char* hardeningKindName(HardeningKind kind) {
  return kind == HardeningKind::linear ? "linear" : "johnson_cook";
}

}  // namespace rupture
