#pragma once
// A run's state, visited once to save it into a checkpoint and once to load it back (docs/checkpoints.md).
// Every stateful part of a run (particle and bond stores, contact lists, SPH particles, shells,
// observables, recorders' rows) lists its members in one `exchangeState(StateArchive&)`: the same
// list saves and loads, so the two can never disagree. Loading replaces each value; a value the
// checkpoint lacks throws CheckpointError.
//
// The interface lives here, below every engine room, so the laws' own headers can list their state
// without knowing the file format (io/hdf5_state_archive.hpp writes it into HDF5). Arrays are
// replaced whole, sizes included (lists grow and shrink while a run goes); a part whose size the
// set-up fixes checks it with expectCount.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace rupture {

/// A checkpoint that cannot be used: missing, unreadable, from another spec, another scenario or
/// an incompatible version. The message says which, for the user (CLI exit code 2, HTTP 409).
class CheckpointError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

class StateArchive {
public:
  virtual ~StateArchive() = default;

  /// True while loading a checkpoint (values are replaced), false while saving one.
  virtual bool loading() const = 0;

  virtual void array(const std::string& name, std::vector<double>& values) = 0;
  virtual void array(const std::string& name, std::vector<std::int32_t>& values) = 0;
  virtual void array(const std::string& name, std::vector<std::uint8_t>& values) = 0;
  virtual void array(const std::string& name, std::vector<std::int64_t>& values) = 0;
  virtual void value(const std::string& name, double& v) = 0;
  virtual void value(const std::string& name, std::int64_t& v) = 0;
  virtual void value(const std::string& name, std::string& v) = 0;

  /// Opens a named group for the calls up to the matching leave().
  virtual void enter(const std::string& name) = 0;
  virtual void leave() = 0;

  // Conveniences over the primitive calls.
  void value(const std::string& name, std::size_t& v) {
    std::int64_t x = static_cast<std::int64_t>(v);
    value(name, x);
    v = static_cast<std::size_t>(x);
  }
  void value(const std::string& name, bool& v) {
    std::int64_t x = v ? 1 : 0;
    value(name, x);
    v = x != 0;
  }
  void value(const std::string& name, int& v) {
    std::int64_t x = v;
    value(name, x);
    v = static_cast<int>(x);
  }
  void array(const std::string& name, std::vector<std::size_t>& values) {
    std::vector<std::int64_t> x(values.begin(), values.end());
    array(name, x);
    values.assign(x.begin(), x.end());
  }
  /// Saves `count`; on loading, throws CheckpointError unless the saved one equals it (a part whose
  /// size the set-up fixed: particles, bonds).
  void expectCount(const std::string& name, std::size_t count) {
    std::size_t saved = count;
    value(name, saved);
    if (loading() && saved != count)
      throw CheckpointError("the checkpoint holds " + std::to_string(saved) + " " + name + ", the run built " +
                            std::to_string(count));
  }
  /// A vector with another allocator (the SPH particles' staggered arrays), through a copy.
  template <class T, class Allocator>
    requires(!std::is_same_v<Allocator, std::allocator<T>>)
  void array(const std::string& name, std::vector<T, Allocator>& values) {
    std::vector<T> copy(values.begin(), values.end());
    array(name, copy);
    if (loading()) values.assign(copy.begin(), copy.end());
  }
  /// A vector of plain records (structs of numbers), kept as their bytes: exact, and the record's
  /// size is checked on loading.
  template <class T>
  void records(const std::string& name, std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    std::vector<std::uint8_t> bytes(values.size() * sizeof(T));
    if (!bytes.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
    array(name, bytes);
    if (!loading()) return;
    if (bytes.size() % sizeof(T) != 0)
      throw CheckpointError("checkpoint value " + name + " holds " + std::to_string(bytes.size()) +
                            " bytes, not whole records of " + std::to_string(sizeof(T)));
    values.resize(bytes.size() / sizeof(T));
    if (!bytes.empty()) std::memcpy(values.data(), bytes.data(), bytes.size());
  }
  /// One plain record (a struct of numbers), kept as its bytes.
  template <class T>
  void record(const std::string& name, T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    std::vector<std::uint8_t> bytes(sizeof(T));
    std::memcpy(bytes.data(), &v, sizeof(T));
    array(name, bytes);
    if (!loading()) return;
    if (bytes.size() != sizeof(T))
      throw CheckpointError("checkpoint value " + name + " holds " + std::to_string(bytes.size()) +
                            " bytes, not one record of " + std::to_string(sizeof(T)));
    std::memcpy(&v, bytes.data(), sizeof(T));
  }
};

/// enter() on construction, leave() on destruction.
class StateGroup {
public:
  StateGroup(StateArchive& archive, const std::string& name) : m_archive(archive) { m_archive.enter(name); }
  ~StateGroup() { m_archive.leave(); }
  StateGroup(const StateGroup&) = delete;
  StateGroup& operator=(const StateGroup&) = delete;

private:
  StateArchive& m_archive;
};

}  // namespace rupture
