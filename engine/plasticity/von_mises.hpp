#pragma once
// Von Mises (J2) elastic–plastic material with isotropic hardening, integrated by return mapping
// (backward Euler, associated flow). Small strains: the stress is a linear function of the elastic
// strain; in the total-Lagrangian shell the strains are Green–Lagrange strains and the stresses
// second Piola–Kirchhoff stresses (large rotations, small strains).
//
//  3D:           radial return (Wilkins 1964; Simo & Hughes 1998, Box 3.1): a scalar equation in
//                the plastic-strain increment Δp,  σ_eq^tr − 3 G Δp − σ_y(p_n + Δp) = 0.
//  plane stress: the projected algorithm of Simo & Taylor (1986) (Simo & Hughes 1998, §3.4;
//                de Souza Neto, Perić & Owen 2008, §9.4.3): σ33 = 0 is kept exactly by returning
//                in the space of the in-plane stresses with the plane-stress projection matrix P;
//                one scalar equation in the plastic multiplier Δγ, solved by a bracketed Newton
//                iteration (works for nonlinear hardening; closed form of the stress for a given
//                Δγ in the common eigenbasis of C and P).
// Everything is data-oriented: one call per array of material points; the per-point kernels are
// inline so that a shell or solid loop can call them inside its own loop.
#include <array>
#include <span>
#include <string>

#include "plasticity/isotropic_hardening.hpp"

namespace rupture {

/// Symmetric 3D tensor (xx, yy, zz, yz, xz, xy), tensor (not engineering) shear components.
using SymTensor3 = std::array<double, 6>;
/// In-plane symmetric tensor (11, 22, 12), tensor shear component; σ33 = σ13 = σ23 = 0.
using PlaneTensor = std::array<double, 3>;
/// The transverse shears (13, 23) of a shell's layer, tensor components, beside its PlaneTensor.
using TransverseShear = std::array<double, 2>;

struct ElasticPlasticMaterial {
  double youngModulus = 73.1e9;  ///< E (Pa)
  double poissonRatio = 0.33;    ///< ν, in (-1, 0.5)
  IsotropicHardening hardening;

  double shearModulus() const { return youngModulus / (2.0 * (1.0 + poissonRatio)); }
  double bulkModulus() const { return youngModulus / (3.0 * (1.0 - 2.0 * poissonRatio)); }
};

/// Throws SpecError naming `<prefix>.young_modulus`, `<prefix>.poisson_ratio` or a hardening field.
void validateElasticPlastic(const ElasticPlasticMaterial& m, const std::string& prefix);

double vonMisesStress(const SymTensor3& s);
double vonMisesStress(const PlaneTensor& s);
/// A shell layer's: σ_eq² = σ11² − σ11 σ22 + σ22² + 3 (σ12² + σ13² + σ23²) (σ33 = 0).
double vonMisesStress(const PlaneTensor& s, const TransverseShear& q);
double hydrostaticStress(const SymTensor3& s);
inline double hydrostaticStress(const PlaneTensor& s) { return (s[0] + s[1]) / 3.0; }

/// Outcome of one return mapping.
struct ReturnMapping {
  double plasticStrainIncrement = 0.0;  ///< Δp >= 0
  double plasticMultiplier = 0.0;       ///< Δγ (plane stress: ε^p increment = Δγ P σ)
  bool plastic = false;
};

/// Corrects a trial stress (in/out) onto the yield surface σ_eq = σ_y(p_n + Δp).
ReturnMapping radialReturn3D(const ElasticPlasticMaterial& m, SymTensor3& stress, double p);

/// Plane-stress projected return (Simo–Taylor): corrects the in-plane trial stress (in/out).
ReturnMapping planeStressReturn(const ElasticPlasticMaterial& m, PlaneTensor& stress, double p);

/// The same with a shell layer's transverse shears σ13, σ23 (in/out) in the yield function: they
/// are shears like σ12 in the eigenbasis of C and P, so the one scalar equation stays.
ReturnMapping shellReturn(const ElasticPlasticMaterial& m, PlaneTensor& stress, TransverseShear& shear, double p);

/// Plane-stress Hooke's law σ = C ε for the in-plane tensor strain ε.
PlaneTensor planeStressElastic(const ElasticPlasticMaterial& m, const PlaneTensor& strain);

/// Strain-driven 3D update over arrays of points: stress += C:Δε, then radial return; the
/// accumulated plastic strain p is updated in place.
void updateStress3D(const ElasticPlasticMaterial& m, std::span<const SymTensor3> strainIncrement,
                    std::span<SymTensor3> stress, std::span<double> plasticStrain);

/// Total-strain plane-stress update over arrays of points: σ = C (ε − ε^p), return mapping,
/// then ε^p (in-plane tensor components) and p are updated in place.
void updateStressPlaneStress(const ElasticPlasticMaterial& m, std::span<const PlaneTensor> totalStrain,
                             std::span<PlaneTensor> plasticStrainTensor,
                             std::span<double> plasticStrain, std::span<PlaneTensor> stress);

/// A shell layer's total-strain update with its transverse tensor shear strains ε13, ε23: σ13 =
/// 2G (ε13 − ε^p_13), shellReturn, then ε^p (in-plane and transverse) and p updated in place.
ReturnMapping shellPointUpdate(const ElasticPlasticMaterial& m, const PlaneTensor& totalStrain,
                               const TransverseShear& transverseStrain, PlaneTensor& plasticStrainTensor,
                               TransverseShear& plasticShear, double& plasticStrain, PlaneTensor& stress,
                               TransverseShear& shear);

/// One point of updateStressPlaneStress (the shell calls this inside its own loop).
ReturnMapping planeStressPointUpdate(const ElasticPlasticMaterial& m, const PlaneTensor& totalStrain,
                                     PlaneTensor& plasticStrainTensor, double& plasticStrain,
                                     PlaneTensor& stress);

}  // namespace rupture
