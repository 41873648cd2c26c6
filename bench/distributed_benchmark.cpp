// W2 over the ranks of an MPI run (engine/distributed): the block decomposed by coordinate
// bisection, each rank stepping its sub-domain with one OpenMP thread (unless OMP_NUM_THREADS says
// otherwise), 1000 steps. Prints one JSON line from rank 0: the throughput of the whole block,
// the bytes the halo exchange sends per step (all ranks), the largest fraction of a rank's step
// spent in the exchange (packing, waiting, unpacking), and the broken bonds (the one-rank count:
// the trajectories are the same bit for bit). bench/README.md, "W2 on several ranks".
//   mpirun -np 2 build/bench/distributed_bench [--steps N]
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

#include <nlohmann/json.hpp>

#include "bonded_bench_report.hpp"
#include "distributed/coordinate_bisection.hpp"
#include "distributed/subdomain.hpp"
#include "host_processor.hpp"
#include "pmb_impact_benchmark.hpp"

using namespace rupture;

int main(int argc, char** argv) {
  MpiSession mpi(argc, argv);
  int steps = 1000;
  for (int a = 1; a < argc; ++a) {
    if (std::strcmp(argv[a], "--steps") == 0 && a + 1 < argc) {
      steps = std::atoi(argv[++a]);
    } else {
      std::cerr << "usage: distributed_bench [--steps N]   (under mpirun -np RANKS)\n";
      return 2;
    }
  }
  if (steps < 1) {
    std::cerr << "--steps: " << steps << " is not allowed (at least 1)\n";
    return 2;
  }
  const Communicator comm = Communicator::world();
  const BondedSystem whole = bench::buildW2Block();
  const double top = *std::max_element(whole.particles.z.begin(), whole.particles.z.end());
  Subdomain d(whole, bisectCoordinates(whole.particles, whole.bonds, comm.size()), comm);
  d.system.externalLoads = bench::w2Indenter(top);
  double exchangeSeconds = 0;
  auto refresh = d.system.refreshGhosts;
  d.system.refreshGhosts = [&](ParticleStore& p, std::vector<double>& nodalMinimum) {
    const auto t0 = std::chrono::steady_clock::now();
    refresh(p, nodalMinimum);
    exchangeSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  d.system.initialize();
  comm.barrier();
  exchangeSeconds = 0;
  const double cpuStart = bench::processCpuSeconds();
  const auto start = std::chrono::steady_clock::now();
  for (int t = 0; t < steps; ++t) d.system.step(bench::kW2TimeStep);
  comm.barrier();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double cpuSeconds = comm.sum(bench::processCpuSeconds() - cpuStart);
  const double waiting = comm.max(exchangeSeconds / seconds);
  const double bytes = comm.sum(static_cast<double>(d.halo().bytesSent()));
  const double ghosts = comm.sum(static_cast<double>(d.system.particles.size() - d.ownedCount()));
  const std::uint64_t broken = d.brokenBonds();
  if (comm.rank() == 0) {
    nlohmann::json report = {{"workload", "W2"},
                             {"ranks", comm.size()},
                             {"threads_per_rank", omp_get_max_threads()},
                             {"particles", whole.particles.size()},
                             {"bonds", whole.bonds.size()},
                             {"steps", steps},
                             {"seconds", seconds},
                             {"cpu_seconds", cpuSeconds},
                             {"particle_steps_per_s", static_cast<double>(whole.particles.size()) * steps / seconds},
                             {"ghosts", ghosts},
                             {"exchange_bytes_per_step", bytes},
                             {"exchange_fraction_max", waiting},
                             {"broken_bonds", broken},
                             {"host", bench::hostProcessor()}};
    std::cout << report.dump() << std::endl;
  }
  return 0;
}
