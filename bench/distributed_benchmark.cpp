// W1 or W2 over the ranks of an MPI run (engine/distributed): the sample decomposed by coordinate
// bisection, each rank stepping its sub-domain with one OpenMP thread (unless OMP_NUM_THREADS says
// otherwise), 1000 steps. Prints one JSON line from rank 0: the throughput of the whole sample,
// the bytes the exchanges send per step (all ranks: the bond ghosts' halo and, for W1, the contact
// ghosts' refresh), the largest fraction of a rank's step spent in them (packing, waiting,
// unpacking), and the broken bonds (the one-rank count: the trajectories are the same bit for
// bit). bench/README.md, "W1 and W2 on several ranks".
//   mpirun -np 2 build/bench/distributed_bench [--workload W1|W2] [--particles N] [--steps N]
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

#include <nlohmann/json.hpp>

#include "bonded_bar_benchmark.hpp"
#include "bonded_bench_report.hpp"
#include "distributed/coordinate_bisection.hpp"
#include "distributed/subdomain.hpp"
#include "host_processor.hpp"
#include "pmb_impact_benchmark.hpp"

using namespace rupture;

int main(int argc, char** argv) {
  MpiSession mpi(argc, argv);
  int steps = 1000;
  std::string workload = "W2";
  long long particles = 102400;  // W1's size; W2's block is fixed
  bool particlesGiven = false;
  for (int a = 1; a < argc; ++a) {
    if (std::strcmp(argv[a], "--steps") == 0 && a + 1 < argc) {
      steps = std::atoi(argv[++a]);
    } else if (std::strcmp(argv[a], "--workload") == 0 && a + 1 < argc) {
      workload = argv[++a];
    } else if (std::strcmp(argv[a], "--particles") == 0 && a + 1 < argc) {
      particles = std::atoll(argv[++a]);
      particlesGiven = true;
    } else {
      std::cerr << "usage: distributed_bench [--workload W1|W2] [--particles N (W1)] [--steps N]   (under mpirun -np RANKS)\n";
      return 2;
    }
  }
  if (steps < 1) {
    std::cerr << "--steps: " << steps << " is not allowed (at least 1)\n";
    return 2;
  }
  if (workload != "W1" && workload != "W2") {
    std::cerr << "--workload: " << workload << " is not allowed (W1 or W2)\n";
    return 2;
  }
  if (particlesGiven && workload != "W1") {
    std::cerr << "--particles: not allowed with " << workload << " (its block is fixed; W1 scales)\n";
    return 2;
  }
  if (particles < 1000 || particles > 100'000'000) {
    std::cerr << "--particles: " << particles << " is not allowed (1000 to 100000000)\n";
    return 2;
  }
  const Communicator comm = Communicator::world();
  const bool w1 = workload == "W1";
  // W1 as `rupture bench W1` runs it: the bar initialised once whole, for its time step.
  BondedSystem whole;
  double dt = bench::kW2TimeStep;
  if (w1) {
    bench::buildW1Bar(whole, static_cast<std::size_t>(particles));
    whole.initialize();
    dt = bench::w1TimeStep(whole);
  } else {
    whole = bench::buildW2Block();
  }
  Subdomain d(whole, bisectCoordinates(whole.particles, whole.bonds, comm.size()), comm);
  if (!w1) d.system.externalLoads = bench::w2Indenter(*std::max_element(whole.particles.z.begin(), whole.particles.z.end()));
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
  for (int t = 0; t < steps; ++t) d.system.step(dt);
  comm.barrier();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double cpuSeconds = comm.sum(bench::processCpuSeconds() - cpuStart);
  const double waiting = comm.max(exchangeSeconds / seconds);
  const ContactHalo* contact = d.contactHalo();
  const double bytes =
      comm.sum(static_cast<double>(d.halo().bytesSent() + (contact != nullptr ? contact->bytesSent() : 0)));
  const double contactGhosts = comm.sum(static_cast<double>(contact != nullptr ? contact->ghostCount() : 0));
  const double ghosts = comm.sum(static_cast<double>(d.system.particles.size() - d.ownedCount()));
  const std::uint64_t broken = d.brokenBonds();
  if (comm.rank() == 0) {
    nlohmann::json report = {{"workload", workload},
                             {"ranks", comm.size()},
                             {"threads_per_rank", omp_get_max_threads()},
                             {"particles", whole.particles.size()},
                             {"bonds", whole.bonds.size()},
                             {"steps", steps},
                             {"seconds", seconds},
                             {"cpu_seconds", cpuSeconds},
                             {"particle_steps_per_s", static_cast<double>(whole.particles.size()) * steps / seconds},
                             {"ghosts", ghosts},
                             {"contact_ghosts", contactGhosts},
                             {"time_step", dt},
                             {"exchange_bytes_per_step", bytes},
                             {"exchange_fraction_max", waiting},
                             {"broken_bonds", broken},
                             {"host", bench::hostProcessor()}};
    std::cout << report.dump() << std::endl;
  }
  return 0;
}
