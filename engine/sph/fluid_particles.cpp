#include "sph/fluid_particles.hpp"

#include "core/parallel.hpp"

namespace rupture::sph {

namespace {

template <class T>
void applyOrder(ParticleArray<T>& field, const std::vector<std::int32_t>& order, ParticleArray<T>& scratch) {
  scratch.resize(field.size());
#pragma omp parallel for schedule(static) if (worthParallel(order.size()))
  for (std::size_t k = 0; k < order.size(); ++k) scratch[k] = field[order[k]];
  field.swap(scratch);
}

}  // namespace

void FluidParticles::add(double px, double py, double pz, double m, double density, std::int32_t bodyIndex) {
  x.push_back(px); y.push_back(py); z.push_back(pz);
  vx.push_back(0); vy.push_back(0); vz.push_back(0);
  rho.push_back(density);
  vxEst.push_back(0); vyEst.push_back(0); vzEst.push_back(0);
  rhoEst.push_back(density);
  pressure.push_back(0);
  ax.push_back(0); ay.push_back(0); az.push_back(0); drho.push_back(0);
  mass.push_back(m);
  body.push_back(bodyIndex);
  id.push_back(static_cast<std::int32_t>(id.size()));
}

void FluidParticles::permute(const std::vector<std::int32_t>& order) {
  ParticleArray<double> d;
  ParticleArray<std::int32_t> i;
  permute(order, d, i);
}

void FluidParticles::permute(const std::vector<std::int32_t>& order, ParticleArray<double>& d,
                             ParticleArray<std::int32_t>& i) {
  // Each field swaps its buffer with the scratch: the buffers (and their offsets within the page)
  // pass from field to field, and stay distinct.
  for (ParticleArray<double>* f : {&x, &y, &z, &vx, &vy, &vz, &rho, &vxEst, &vyEst, &vzEst, &rhoEst, &pressure, &ax, &ay, &az, &drho, &mass})
    applyOrder(*f, order, d);
  applyOrder(body, order, i);
  applyOrder(id, order, i);
}

void FluidParticles::inCreationOrder(std::span<const double> field, std::vector<double>& out) const {
  out.resize(field.size());
  for (std::size_t k = 0; k < field.size(); ++k) out[id[k]] = field[k];
}

void FluidParticles::exchangeState(StateArchive& archive) {
  StateGroup group(archive, "particles");
  archive.expectCount("particles", size());
  archive.array("x", x), archive.array("y", y), archive.array("z", z);
  archive.array("vx", vx), archive.array("vy", vy), archive.array("vz", vz);
  archive.array("rho", rho);
  archive.array("vx_est", vxEst), archive.array("vy_est", vyEst), archive.array("vz_est", vzEst);
  archive.array("rho_est", rhoEst);
  archive.array("pressure", pressure);
  archive.array("ax", ax), archive.array("ay", ay), archive.array("az", az), archive.array("drho", drho);
  archive.array("mass", mass);
  archive.array("body", body), archive.array("id", id);
}

}  // namespace rupture::sph
