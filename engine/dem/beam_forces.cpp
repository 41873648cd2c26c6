#include "dem/beam_forces.hpp"

#include "core/parallel.hpp"

namespace rupture {

BeamResponse beamResponseOf(const BeamParameters& beam, const ParticleStore& p, const BondStore& bonds,
                            std::size_t b) {
  const std::int32_t i = bonds.i[b], j = bonds.j[b];
  return beamResponse(beam, p.radius[i], p.radius[j], bonds.restLength[b], bonds.n0x[b], bonds.n0y[b],
                      bonds.n0z[b], p.x[j] - p.x[i], p.y[j] - p.y[i], p.z[j] - p.z[i], p.qw[i], p.qx[i],
                      p.qy[i], p.qz[i], p.qw[j], p.qx[j], p.qy[j], p.qz[j]);
}

std::size_t computeBeamLoads(const BeamParameters& beam, const ParticleStore& p, BondStore& bonds) {
  // Bind the arrays to local pointers: the loop body is then plain loads, arithmetic and stores.
  const std::int32_t* bi = bonds.i.data();
  const std::int32_t* bj = bonds.j.data();
  const double *L0 = bonds.restLength.data(), *n0x = bonds.n0x.data(), *n0y = bonds.n0y.data(),
               *n0z = bonds.n0z.data();
  double* intact = bonds.intact.data();
  double *fjx = bonds.fjx.data(), *fjy = bonds.fjy.data(), *fjz = bonds.fjz.data();
  double *tix = bonds.tix.data(), *tiy = bonds.tiy.data(), *tiz = bonds.tiz.data();
  double *tjx = bonds.tjx.data(), *tjy = bonds.tjy.data(), *tjz = bonds.tjz.data();
  double* sigma = bonds.equivalentStress.data();
  const double *x = p.x.data(), *y = p.y.data(), *z = p.z.data(), *rad = p.radius.data();
  const double *qw = p.qw.data(), *qx = p.qx.data(), *qy = p.qy.data(), *qz = p.qz.data();
  const BeamParameters law = beam;
  // σ_f <= 0 means unbreakable.
  const double threshold = law.failureStress > 0 ? law.failureStress : 1e308;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(bonds.size());
  const bool parallel = worthParallel(bonds.size());
  std::size_t broken = 0;

#pragma omp parallel for simd schedule(static) reduction(+ : broken) firstprivate(law, threshold) if (parallel)
  for (std::ptrdiff_t b = 0; b < n; ++b) {
    const std::int32_t i = bi[b], j = bj[b];
    const BeamResponse r =
        beamResponse(law, rad[i], rad[j], L0[b], n0x[b], n0y[b], n0z[b], x[j] - x[i], y[j] - y[i],
                     z[j] - z[i], qw[i], qx[i], qy[i], qz[i], qw[j], qx[j], qy[j], qz[j]);
    // Arithmetic instead of && so the loop has no control flow: now = was · [σ_eq < σ_f].
    const double was = intact[b];
    const double now = was * static_cast<double>(r.equivalentStress < threshold);
    broken += static_cast<std::size_t>(was - now);
    intact[b] = now;
    sigma[b] = r.equivalentStress;
    fjx[b] = now * r.fjx; fjy[b] = now * r.fjy; fjz[b] = now * r.fjz;
    tix[b] = now * r.tix; tiy[b] = now * r.tiy; tiz[b] = now * r.tiz;
    tjx[b] = now * r.tjx; tjy[b] = now * r.tjy; tjz[b] = now * r.tjz;
  }
  return broken;
}

void gatherBondLoads(const BondStore& bonds, ParticleStore& p) {
  const std::int32_t* start = bonds.incidenceStart.data();
  const std::int32_t* inc = bonds.incidence.data();
  const double *fjx = bonds.fjx.data(), *fjy = bonds.fjy.data(), *fjz = bonds.fjz.data();
  const double *tix = bonds.tix.data(), *tiy = bonds.tiy.data(), *tiz = bonds.tiz.data();
  const double *tjx = bonds.tjx.data(), *tjy = bonds.tjy.data(), *tjz = bonds.tjz.data();
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(p.size());
#pragma omp parallel for schedule(static) if (worthParallel(p.size()))
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    double fx = 0, fy = 0, fz = 0, tx = 0, ty = 0, tz = 0;
    for (std::int32_t s = start[k]; s < start[k + 1]; ++s) {
      const std::int32_t e = inc[s], b = e >> 1;
      const double sign = (e & 1) ? 1.0 : -1.0;  // end j receives F_j, end i receives −F_j
      fx += sign * fjx[b]; fy += sign * fjy[b]; fz += sign * fjz[b];
      tx += (e & 1) ? tjx[b] : tix[b];
      ty += (e & 1) ? tjy[b] : tiy[b];
      tz += (e & 1) ? tjz[b] : tiz[b];
    }
    p.fx[k] = fx; p.fy[k] = fy; p.fz[k] = fz;
    p.tx[k] = tx; p.ty[k] = ty; p.tz[k] = tz;
  }
}

double beamElasticEnergy(const BeamParameters& beam, const ParticleStore& p, const BondStore& bonds) {
  double e = 0;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(bonds.size());
#pragma omp parallel for reduction(+ : e) schedule(static)
  for (std::ptrdiff_t b = 0; b < n; ++b)
    if (bonds.intact[b] > 0.5) e += beamResponseOf(beam, p, bonds, b).energy;
  return e;
}

}  // namespace rupture
