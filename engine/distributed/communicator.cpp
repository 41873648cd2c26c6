#include "distributed/communicator.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>

#ifdef RUPTURE_HAVE_MPI
#include <mpi.h>
#endif
#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace rupture {

#ifdef RUPTURE_HAVE_MPI

namespace {

/// Blocks this large or larger get their own mapping on several ranks (MpiSession).
constexpr int kOwnMappingBytes = 1 << 20;

bool mpiRunning() {
  int initialised = 0, finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  return initialised && !finalised;
}

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed (error " + std::to_string(code) + ")");
}

/// Each rank's offset in the concatenation of counts[r] items from every rank r; returns the total.
std::size_t offsetsOf(const std::vector<int>& counts, std::vector<int>& offsets) {
  offsets.resize(counts.size());
  std::size_t total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    offsets[r] = static_cast<int>(total);
    total += static_cast<std::size_t>(counts[r]);
  }
  return total;
}

template <class T>
std::vector<T> gatherConcatenated(const std::vector<T>& mine, MPI_Datatype type, int size) {
  const int count = static_cast<int>(mine.size());
  std::vector<int> counts(size), offsets;
  check(MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD), "MPI_Allgather");
  std::vector<T> all(offsetsOf(counts, offsets));
  check(MPI_Allgatherv(mine.data(), count, type, all.data(), counts.data(), offsets.data(), type, MPI_COMM_WORLD),
        "MPI_Allgatherv");
  return all;
}

template <class T>
std::vector<T> gatherConcatenatedToFirst(const std::vector<T>& mine, MPI_Datatype type, int rank, int size) {
  const int count = static_cast<int>(mine.size());
  std::vector<int> counts(rank == 0 ? size : 0), offsets;  // the counts only where they arrive
  check(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Gather");
  std::vector<T> all(offsetsOf(counts, offsets));
  check(MPI_Gatherv(mine.data(), count, type, all.data(), counts.data(), offsets.data(), type, 0, MPI_COMM_WORLD),
        "MPI_Gatherv");
  return all;
}

}  // namespace

Communicator Communicator::world() {
  if (!mpiRunning()) return Communicator(0, 1);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return Communicator(rank, size);
}

void Communicator::exchange(const std::vector<Message>& sends, const std::vector<Message>& receives) const {
  if (m_size == 1) return;
  std::vector<MPI_Request> requests;
  requests.reserve(sends.size() + receives.size());
  constexpr int kTag = 17;
  for (const Message& m : receives) {
    requests.emplace_back();
    check(MPI_Irecv(m.data, static_cast<int>(m.count), MPI_DOUBLE, m.peer, kTag, MPI_COMM_WORLD, &requests.back()),
          "MPI_Irecv");
  }
  for (const Message& m : sends) {
    requests.emplace_back();
    check(MPI_Isend(m.data, static_cast<int>(m.count), MPI_DOUBLE, m.peer, kTag, MPI_COMM_WORLD, &requests.back()),
          "MPI_Isend");
  }
  check(MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE), "MPI_Waitall");
}

double Communicator::sum(double value) const {
  if (m_size == 1) return value;
  double total = 0;
  check(MPI_Allreduce(&value, &total, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD), "MPI_Allreduce");
  return total;
}

std::uint64_t Communicator::sum(std::uint64_t value) const {
  if (m_size == 1) return value;
  std::uint64_t total = 0;
  check(MPI_Allreduce(&value, &total, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD), "MPI_Allreduce");
  return total;
}

double Communicator::max(double value) const {
  if (m_size == 1) return value;
  double largest = 0;
  check(MPI_Allreduce(&value, &largest, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD), "MPI_Allreduce");
  return largest;
}

std::vector<double> Communicator::allGather(const std::vector<double>& mine) const {
  if (m_size == 1) return mine;
  return gatherConcatenated(mine, MPI_DOUBLE, m_size);
}

std::vector<std::int64_t> Communicator::allGather(const std::vector<std::int64_t>& mine) const {
  if (m_size == 1) return mine;
  return gatherConcatenated(mine, MPI_INT64_T, m_size);
}

std::vector<double> Communicator::allGather(const std::vector<double>& mine, const std::vector<int>& counts) const {
  if (m_size == 1) return mine;
  if (counts.size() != static_cast<std::size_t>(m_size) || counts[static_cast<std::size_t>(m_rank)] != static_cast<int>(mine.size()))
    throw std::logic_error("Communicator::allGather: the counts do not match the ranks' vectors");
  std::vector<int> offsets;
  std::vector<double> all(offsetsOf(counts, offsets));
  check(MPI_Allgatherv(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
                       MPI_DOUBLE, MPI_COMM_WORLD),
        "MPI_Allgatherv");
  return all;
}

std::vector<double> Communicator::gatherToFirst(const std::vector<double>& mine) const {
  if (m_size == 1) return mine;
  return gatherConcatenatedToFirst(mine, MPI_DOUBLE, m_rank, m_size);
}

std::vector<std::int64_t> Communicator::gatherToFirst(const std::vector<std::int64_t>& mine) const {
  if (m_size == 1) return mine;
  return gatherConcatenatedToFirst(mine, MPI_INT64_T, m_rank, m_size);
}

bool Communicator::broadcastFromFirst(bool value) const {
  if (m_size == 1) return value;
  int flag = value ? 1 : 0;
  check(MPI_Bcast(&flag, 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Bcast");
  return flag != 0;
}

void Communicator::barrier() const {
  if (m_size > 1) check(MPI_Barrier(MPI_COMM_WORLD), "MPI_Barrier");
}

MpiSession::MpiSession(int& argc, char**& argv) {
  int provided = 0;
  check(MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided), "MPI_Init_thread");
  if (provided < MPI_THREAD_SERIALIZED) {
    MPI_Finalize();
    throw std::runtime_error("MPI: this MPI library does not let one thread at a time call it (MPI_THREAD_SERIALIZED)");
  }
#ifdef __GLIBC__
  // Under an MPI launcher, every block of 1 MiB or more in its own mapping (glibc's threshold fixed
  // instead of its dynamic one, which rises as large blocks are freed and then serves them from the
  // heap). Two reasons, both measured (docs/distributed.md): the whole sample a rank drops once its
  // sub-domain is cut goes back to the system at once (from the heap it stayed resident), and the
  // sub-domain's per-bond arrays all start 16 bytes into a page, so that the vectorised bond loop
  // peels once to align all its streams (from the heap, at scattered offsets, W1's steps on two
  // ranks took 14.0 s instead of 11.0 s). On one rank too, so that a one-rank reference is cut and
  // placed as each of several ranks is.
  mallopt(M_MMAP_THRESHOLD, kOwnMappingBytes);
#endif
}

MpiSession::~MpiSession() {
  if (mpiRunning()) MPI_Finalize();
}

void MpiSession::abortJob(int code) {
  if (mpiRunning() && Communicator::world().size() > 1) MPI_Abort(MPI_COMM_WORLD, code);
}

#else  // one rank: every call is the identity

Communicator Communicator::world() { return Communicator(0, 1); }
void Communicator::exchange(const std::vector<Message>& sends, const std::vector<Message>& receives) const {
  if (!sends.empty() || !receives.empty())
    throw std::logic_error("Communicator::exchange: messages to other ranks in a build without MPI");
}
double Communicator::sum(double value) const { return value; }
std::uint64_t Communicator::sum(std::uint64_t value) const { return value; }
double Communicator::max(double value) const { return value; }
std::vector<double> Communicator::allGather(const std::vector<double>& mine) const { return mine; }
std::vector<double> Communicator::allGather(const std::vector<double>& mine, const std::vector<int>&) const { return mine; }
std::vector<std::int64_t> Communicator::allGather(const std::vector<std::int64_t>& mine) const { return mine; }
std::vector<double> Communicator::gatherToFirst(const std::vector<double>& mine) const { return mine; }
std::vector<std::int64_t> Communicator::gatherToFirst(const std::vector<std::int64_t>& mine) const { return mine; }
bool Communicator::broadcastFromFirst(bool value) const { return value; }
void Communicator::barrier() const {}
MpiSession::MpiSession(int&, char**&) {
  // N copies of a one-rank run would each write the whole result to the same file.
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* size = std::getenv(variable); size != nullptr && std::atoi(size) > 1)
      throw std::runtime_error(std::string("this rupture was built without MPI (RUPTURE_MPI off, or no libopenmpi-dev) "
                                           "but was started as one of ") + size + " ranks; run it alone, or rebuild with MPI");
}
MpiSession::~MpiSession() = default;
void MpiSession::abortJob(int) {}

#endif

bool MpiSession::launched() {
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(variable) != nullptr) return true;
  return false;
}

}  // namespace rupture
