#pragma once
// The cohesive beam (dem/beam_bond.hpp) as a bond law of the generic loop (core/bond_loop.hpp).
// A bond's stiffness slot (BondGeometry::stiffness) is its factor on E_μ (1 but for disorder or
// inclusions): every load, the energy and the Rankine stress are proportional to E_μ at fixed ν_μ,
// so the beam of modulus f·E_μ is exactly the beam law of those parameters.
#include <cmath>

#include "core/bond_law.hpp"
#include "dem/beam_bond.hpp"

namespace rupture {

struct BeamLaw {
  static constexpr const char* kName = "beam";
  static constexpr bool kRotational = true;
  BeamParameters params;

  /// The parameters of the bond's own beam: E_μ times its factor.
  [[gnu::always_inline]] BeamParameters bondParameters(const BondGeometry& g) const {
    BeamParameters p = params;
    p.youngModulus *= g.stiffness;
    return p;
  }

  [[gnu::always_inline]] BondResponse response(const BondGeometry& g) const {
    const BeamParameters own = bondParameters(g);
    const BeamResponse b = beamResponse(own, g.radiusI, g.radiusJ, g.restLength, g.n0x, g.n0y, g.n0z, g.dx, g.dy,
                                        g.dz, g.qiw, g.qix, g.qiy, g.qiz, g.qjw, g.qjx, g.qjy, g.qjz);
    const BeamSection sec = BeamSection::of(own, g.radiusI, g.radiusJ);
    const double kAxial = own.youngModulus * sec.area / g.restLength;
    const double stretch = b.axialForce / (kAxial * g.restLength);
    const double axialEnergy = 0.5 * b.axialForce * b.axialForce / kAxial;
    BondResponse r;
    r.fjx = b.fjx; r.fjy = b.fjy; r.fjz = b.fjz;
    r.tix = b.tix; r.tiy = b.tiy; r.tiz = b.tiz;
    r.tjx = b.tjx; r.tjy = b.tjy; r.tjz = b.tjz;
    r.energy = b.energy;
    r.stretch = stretch;
    r.normalForce = b.axialForce;
    r.tensileNormalEnergy = stretch > 0 ? axialEnergy : 0.0;
    r.shearEnergy = b.energy - axialEnergy;
    r.equivalentStress = b.equivalentStress;
    return r;
  }

  /// The same law under planar motion (2D; core/bond_loop.hpp's kPlanar): only F_x, F_y, T_z
  /// and σ_eq are filled, the rest is 0.
  [[gnu::always_inline]] BondResponse planarResponse(const BondGeometry& g) const {
    const PlanarBeamResponse b = planarBeamResponse(bondParameters(g), g.radiusI, g.radiusJ, g.restLength, g.n0x, g.n0y, g.dx,
                                                    g.dy, g.qiw, g.qiz, g.qjw, g.qjz);
    BondResponse r{};
    r.fjx = b.fjx; r.fjy = b.fjy;
    r.tiz = b.tiz; r.tjz = b.tjz;
    r.equivalentStress = b.equivalentStress;
    return r;
  }

  /// The elastic energy of planarResponse's configuration (response(g).energy, the same number).
  [[gnu::always_inline]] double planarEnergy(const BondGeometry& g) const {
    return planarBeamEnergy(bondParameters(g), g.radiusI, g.radiusJ, g.restLength, g.n0x, g.n0y, g.dx, g.dy, g.qiw, g.qiz,
                            g.qjw, g.qjz);
  }

  /// Gershgorin stiffnesses (docs/references.md#eq-gershgorin): k_tr = max(E S/L0, 12 E I/L0³),
  /// k_rot = max(G J/L0, 4 E I/L0).
  BondStiffness stiffness(const BondGeometry& g) const {
    const BeamParameters own = bondParameters(g);
    const BeamSection s = BeamSection::of(own, g.radiusI, g.radiusJ);
    const double E = own.youngModulus, G = own.shearModulus(), L0 = g.restLength;
    return {std::fmax(E * s.area / L0, 12.0 * E * s.secondMoment / (L0 * L0 * L0)),
            std::fmax(G * s.polarMoment / L0, 4.0 * E * s.secondMoment / L0)};
  }
};

}  // namespace rupture
