#include "dem/beam_forces.hpp"


namespace rupture {

BeamResponse beamResponseOf(const BeamParameters& beam, const ParticleStore& p, const BondStore& bonds,
                            std::size_t b) {
  const std::int32_t i = bonds.i[b], j = bonds.j[b];
  BeamParameters own = beam;  // the bond's beam: E_μ times its stiffness factor (dem/beam_law.hpp)
  own.youngModulus *= bonds.stiffness[b];
  return beamResponse(own, p.radius[i], p.radius[j], bonds.restLength[b], bonds.n0x[b], bonds.n0y[b],
                      bonds.n0z[b], p.x[j] - p.x[i], p.y[j] - p.y[i], p.z[j] - p.z[i], p.qw[i], p.qx[i],
                      p.qy[i], p.qz[i], p.qw[j], p.qx[j], p.qy[j], p.qz[j]);
}

}  // namespace rupture
