#pragma once
// The parameters of the weakly compressible SPH fluid (Caleyron et al. 2013 §4.2; docs/references.md#eq-sph):
// kernel, equation of state, Monaghan artificial viscosity, δ-SPH density diffusion, gravity.
// One validated value type: the spec parsers fill it, the pair loop reads it.
#include <array>
#include <string>

#include "sph/cubic_spline_kernel.hpp"
#include "sph/equation_of_state.hpp"

namespace rupture::sph {

/// Density diffusion in the continuity equation (δ-SPH):
///   off
///   molteni_colagrossi: D_a = 2 δ h c0 Σ_b (ρ_a − ρ_b) F_ab V_b           (Molteni & Colagrossi 2009)
///   fourtakas:          the same with the hydrostatic part of ρ_a − ρ_b removed (Fourtakas et al. 2019),
///                       so a column at rest is not diffused towards uniform density.
/// F_ab = (dW/dr)/r, V_b = m_b/ρ_b; only fluid–fluid pairs diffuse.
enum class DiffusionModel { Off, MolteniColagrossi, Fourtakas };

inline std::string toString(DiffusionModel m) {
  switch (m) {
    case DiffusionModel::Off: return "off";
    case DiffusionModel::MolteniColagrossi: return "molteni_colagrossi";
    case DiffusionModel::Fourtakas: return "fourtakas";
  }
  return "?";
}

struct FluidModel {
  int dimension = 3;
  double spacing = 0.01;            ///< initial particle spacing dx (m)
  double smoothingRatio = 1.3;      ///< h/dx (1); kernel support 2h
  EquationOfState eos;
  double alpha = 0.1;               ///< Monaghan viscosity, linear term (1)
  double beta = 0.0;                ///< Monaghan viscosity, quadratic term (1)
  DiffusionModel diffusion = DiffusionModel::Fourtakas;
  double delta = 0.1;               ///< δ (1)
  std::array<double, 3> gravity{0, 0, 0};  ///< m/s²

  double h() const { return smoothingRatio * spacing; }
  CubicSplineKernel kernel() const { return CubicSplineKernel(dimension, h()); }
};

}  // namespace rupture::sph
