#pragma once
// The ranks one run is spread over: MPI_COMM_WORLD when Rupture is built with MPI
// (RUPTURE_HAVE_MPI, Debian's Open MPI found by CMake's FindMPI) and the process was started by
// mpirun or srun; one rank otherwise, with the same calls. Every MPI call of the engine goes through
// here, so that the rest of engine/distributed reads the same with and without MPI.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace rupture {

class Communicator {
public:
  /// All the processes of the run (MPI_COMM_WORLD; one rank without MPI or before MpiSession).
  static Communicator world();
  /// This process alone, with every call the identity (a one-process reference inside an MPI run).
  static Communicator self() { return Communicator(0, 1); }

  int rank() const { return m_rank; }
  int size() const { return m_size; }

  /// A block of doubles sent to or received from one other rank.
  struct Message {
    int peer;
    double* data;
    std::size_t count;
  };
  /// Posts every receive and send at once (non-blocking) and waits for all of them: the halo
  /// exchange. The pairs must match: what rank r sends to s, s receives from r, of the same count.
  void exchange(const std::vector<Message>& sends, const std::vector<Message>& receives) const;

  /// Sum over the ranks, on every rank. The order of the sum is MPI's: the same on every rank, but
  /// not the order of a one-rank sum (round-off).
  double sum(double value) const;
  std::uint64_t sum(std::uint64_t value) const;
  double max(double value) const;

  /// Every rank's vector, concatenated in rank order, on every rank.
  std::vector<double> allGather(const std::vector<double>& mine) const;
  std::vector<std::int64_t> allGather(const std::vector<std::int64_t>& mine) const;
  /// The same when every rank's count is known beforehand (counts[r] of rank r, the same vector on
  /// every rank): one collective instead of two.
  std::vector<double> allGather(const std::vector<double>& mine, const std::vector<int>& counts) const;

  /// Every rank's vector, concatenated in rank order, on the first rank; empty on the others (the
  /// outputs, which only the first rank computes and writes).
  std::vector<double> gatherToFirst(const std::vector<double>& mine) const;
  std::vector<std::int64_t> gatherToFirst(const std::vector<std::int64_t>& mine) const;
  /// The first rank's value, on every rank (a decision only the first rank can take).
  bool broadcastFromFirst(bool value) const;

  /// Waits until every rank has come here.
  void barrier() const;

private:
  Communicator(int rank, int size) : m_rank(rank), m_size(size) {}
  int m_rank = 0, m_size = 1;
};

/// Initialises MPI for the life of the object and finalises it; does nothing without MPI. One per
/// process, in main. Serialized: one thread at a time calls MPI (the CLI runs a spec on a worker
/// thread while its main thread draws the progress; OpenMP threads never call MPI). It also gives
/// every block of 1 MiB or more its own mapping (glibc's mmap threshold), so that memory a rank
/// frees goes back to the system and large arrays start alike within a page.
class MpiSession {
public:
  MpiSession(int& argc, char**& argv);
  /// True when a launcher started this process as a rank of a parallel job: Open MPI's mpirun,
  /// a PMI or PMIx launcher (MPICH's hydra, srun). Without one, a program need not start MPI at all.
  static bool launched();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  /// On more than one rank, ends every rank of the job with `code` (MPI_Abort): for a failure of
  /// this rank alone, which would leave the others waiting. Returns on one rank or without MPI.
  static void abortJob(int code);
};

}  // namespace rupture
