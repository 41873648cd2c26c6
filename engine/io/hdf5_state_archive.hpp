#pragma once
// The StateArchive of a checkpoint file: each array a dataset and each value an attribute under the
// checkpoint's state group, named as the parts name them (/checkpoint/state/system/particles/x, ...).
// Datasets are stored uncompressed: a checkpoint is written often and read once.
#include <string>
#include <vector>

#include "io/hdf5_file.hpp"
#include "rupture/state_archive.hpp"

namespace rupture::io {

class Hdf5StateArchive : public StateArchive {
public:
  enum class Mode { Save, Load };
  /// `root`: the group holding the state (created when saving).
  Hdf5StateArchive(Hdf5File& file, std::string root, Mode mode);

  bool loading() const override { return m_mode == Mode::Load; }
  void array(const std::string& name, std::vector<double>& values) override;
  void array(const std::string& name, std::vector<std::int32_t>& values) override;
  void array(const std::string& name, std::vector<std::uint8_t>& values) override;
  void array(const std::string& name, std::vector<std::int64_t>& values) override;
  void value(const std::string& name, double& v) override;
  void value(const std::string& name, std::int64_t& v) override;
  void value(const std::string& name, std::string& v) override;
  void enter(const std::string& name) override;
  void leave() override;
  using StateArchive::array;
  using StateArchive::value;

private:
  std::string group() const;
  std::string path(const std::string& name) const;
  /// Throws CheckpointError naming the value when a loaded checkpoint lacks it.
  void requireDataset(const std::string& name) const;
  void requireAttribute(const std::string& name) const;
  template <class T>
  void integerArray(const std::string& name, std::vector<T>& values);

  Hdf5File& m_file;
  Mode m_mode;
  std::vector<std::string> m_groups;  ///< m_groups[0] is the root
};

}  // namespace rupture::io
