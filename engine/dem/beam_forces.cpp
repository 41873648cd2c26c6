#include "dem/beam_forces.hpp"


namespace rupture {

BeamResponse beamResponseOf(const BeamParameters& beam, const ParticleStore& p, const BondStore& bonds,
                            std::size_t b) {
  const std::int32_t i = bonds.i[b], j = bonds.j[b];
  // The bond's beam, E_μ times its stiffness factor: the law of E_μ scaled, as the bond loop does
  // (dem/beam_law.hpp).
  BeamResponse r = beamResponse(beam, p.radius[i], p.radius[j], bonds.restLength[b], bonds.n0x[b], bonds.n0y[b],
                                bonds.n0z[b], p.x[j] - p.x[i], p.y[j] - p.y[i], p.z[j] - p.z[i], p.qw[i], p.qx[i],
                                p.qy[i], p.qz[i], p.qw[j], p.qx[j], p.qy[j], p.qz[j]);
  const double f = bonds.stiffness[b];
  for (double* load : {&r.fjx, &r.fjy, &r.fjz, &r.tix, &r.tiy, &r.tiz, &r.tjx, &r.tjy, &r.tjz, &r.equivalentStress,
                       &r.energy, &r.axialForce})
    *load *= f;
  return r;
}

}  // namespace rupture
