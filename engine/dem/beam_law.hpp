#pragma once
// The cohesive beam (dem/beam_bond.hpp) as a bond law of the generic loop (core/bond_loop.hpp).
// A bond's stiffness slot (BondGeometry::stiffness) is its factor f on E_μ (1 but for disorder or
// inclusions): every load, the energy and the Rankine stress are proportional to E_μ at fixed ν_μ,
// so the beam of modulus f·E_μ is the beam law of E_μ scaled by f.
#include <cmath>

#include "core/bond_law.hpp"
#include "dem/beam_bond.hpp"

namespace rupture {

struct BeamLaw {
  static constexpr const char* kName = "beam";
  static constexpr bool kRotational = true;
  BeamParameters params;

  // The law is evaluated with the one set of parameters, whose constants (G_μ, the section's
  // factors) the loop hoists, and scaled by the bond's factor f afterwards: the beam of modulus f·E_μ
  // has f times the loads, energy and σ_eq (homogeneous of degree 1 in σ and τ) of the beam of E_μ.
  // Multiplying by f = 1 is exact, so without disorder or inclusions the loads are those of the
  // unscaled law bit for bit. Building each bond's own parameters instead made the W1 loop half as
  // fast (e68feec; bench/README.md, "Options off and on").

  [[gnu::always_inline]] BondResponse response(const BondGeometry& g) const {
    const double f = g.stiffness;
    const BeamResponse b = beamResponse(params, g.radiusI, g.radiusJ, g.restLength, g.n0x, g.n0y, g.n0z, g.dx, g.dy,
                                        g.dz, g.qiw, g.qix, g.qiy, g.qiz, g.qjw, g.qjx, g.qjy, g.qjz);
    const BeamSection sec = BeamSection::of(params, g.radiusI, g.radiusJ);
    const double kAxial = params.youngModulus * sec.area / g.restLength;
    const double stretch = b.axialForce / (kAxial * g.restLength);
    const double axialEnergy = 0.5 * b.axialForce * b.axialForce / kAxial;
    BondResponse r;
    r.fjx = f * b.fjx; r.fjy = f * b.fjy; r.fjz = f * b.fjz;
    r.tix = f * b.tix; r.tiy = f * b.tiy; r.tiz = f * b.tiz;
    r.tjx = f * b.tjx; r.tjy = f * b.tjy; r.tjz = f * b.tjz;
    r.energy = f * b.energy;
    r.stretch = stretch;
    r.normalForce = f * b.axialForce;
    r.tensileNormalEnergy = stretch > 0 ? f * axialEnergy : 0.0;
    r.shearEnergy = f * (b.energy - axialEnergy);
    r.equivalentStress = f * b.equivalentStress;
    return r;
  }

  /// The same law under planar motion (2D; core/bond_loop.hpp's kPlanar): only F_x, F_y, T_z
  /// and σ_eq are filled, the rest is 0.
  [[gnu::always_inline]] BondResponse planarResponse(const BondGeometry& g) const {
    const double f = g.stiffness;
    const PlanarBeamResponse b = planarBeamResponse(params, g.radiusI, g.radiusJ, g.restLength, g.n0x, g.n0y, g.dx,
                                                    g.dy, g.qiw, g.qiz, g.qjw, g.qjz);
    BondResponse r{};
    r.fjx = f * b.fjx; r.fjy = f * b.fjy;
    r.tiz = f * b.tiz; r.tjz = f * b.tjz;
    r.equivalentStress = f * b.equivalentStress;
    return r;
  }

  /// The elastic energy of planarResponse's configuration (response(g).energy, the same number).
  [[gnu::always_inline]] double planarEnergy(const BondGeometry& g) const {
    return g.stiffness * planarBeamEnergy(params, g.radiusI, g.radiusJ, g.restLength, g.n0x, g.n0y, g.dx, g.dy,
                                          g.qiw, g.qiz, g.qjw, g.qjz);
  }

  /// Gershgorin stiffnesses (docs/references.md#eq-gershgorin): k_tr = max(E S/L0, 12 E I/L0³),
  /// k_rot = max(G J/L0, 4 E I/L0), with E = f·E_μ (G in proportion).
  BondStiffness stiffness(const BondGeometry& g) const {
    const BeamSection s = BeamSection::of(params, g.radiusI, g.radiusJ);
    const double E = params.youngModulus, G = params.shearModulus(), L0 = g.restLength, f = g.stiffness;
    return {f * std::fmax(E * s.area / L0, 12.0 * E * s.secondMoment / (L0 * L0 * L0)),
            f * std::fmax(G * s.polarMoment / L0, 4.0 * E * s.secondMoment / L0)};
  }
};

}  // namespace rupture
