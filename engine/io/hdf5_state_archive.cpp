#include "io/hdf5_state_archive.hpp"

namespace rupture::io {

Hdf5StateArchive::Hdf5StateArchive(Hdf5File& file, std::string root, Mode mode)
    : m_file(file), m_mode(mode), m_groups{std::move(root)} {
  if (m_mode == Mode::Save) {
    m_file.setCompression(false);
    m_file.createGroup(m_groups.front());
  } else if (!m_file.exists(m_groups.front())) {
    throw CheckpointError("the checkpoint " + m_file.path() + " holds no state (" + m_groups.front() + ")");
  }
}

std::string Hdf5StateArchive::group() const {
  std::string g;
  for (const std::string& part : m_groups) g += (g.empty() || g.back() == '/' ? "" : "/") + part;
  return g;
}

std::string Hdf5StateArchive::path(const std::string& name) const { return group() + "/" + name; }

void Hdf5StateArchive::enter(const std::string& name) {
  m_groups.push_back(name);
  if (m_mode == Mode::Save) m_file.createGroup(group());
}

void Hdf5StateArchive::leave() {
  if (m_groups.size() > 1) m_groups.pop_back();
}

void Hdf5StateArchive::requireDataset(const std::string& name) const {
  if (!m_file.exists(path(name)))
    throw CheckpointError("the checkpoint lacks " + path(name) + " (written by another version of this scenario?)");
}

void Hdf5StateArchive::requireAttribute(const std::string& name) const {
  if (!m_file.exists(group()) || !m_file.hasAttribute(group(), name))
    throw CheckpointError("the checkpoint lacks " + group() + "@" + name +
                          " (written by another version of this scenario?)");
}

void Hdf5StateArchive::array(const std::string& name, std::vector<double>& values) {
  if (m_mode == Mode::Save) {
    m_file.writeDataset(path(name), values, {values.size()}, "");
    return;
  }
  requireDataset(name);
  values = m_file.readDatasetDouble(path(name));
}

template <class T>
void Hdf5StateArchive::integerArray(const std::string& name, std::vector<T>& values) {
  if (m_mode == Mode::Save) {
    m_file.writeDataset(path(name), values, {values.size()}, "");
    return;
  }
  requireDataset(name);
  const std::vector<std::int64_t> read = m_file.readDatasetInt(path(name));
  values.assign(read.begin(), read.end());
}

void Hdf5StateArchive::array(const std::string& name, std::vector<std::int32_t>& values) { integerArray(name, values); }
void Hdf5StateArchive::array(const std::string& name, std::vector<std::uint8_t>& values) { integerArray(name, values); }
void Hdf5StateArchive::array(const std::string& name, std::vector<std::int64_t>& values) { integerArray(name, values); }

void Hdf5StateArchive::value(const std::string& name, double& v) {
  if (m_mode == Mode::Save) {
    m_file.setAttribute(group(), name, v);
    return;
  }
  requireAttribute(name);
  v = m_file.readAttributeDouble(group(), name);
}

void Hdf5StateArchive::value(const std::string& name, std::int64_t& v) {
  if (m_mode == Mode::Save) {
    m_file.setAttribute(group(), name, v);
    return;
  }
  requireAttribute(name);
  v = m_file.readAttributeInt(group(), name);
}

void Hdf5StateArchive::value(const std::string& name, std::string& v) {
  if (m_mode == Mode::Save) {
    m_file.setAttribute(group(), name, v);
    return;
  }
  requireAttribute(name);
  v = m_file.readAttributeString(group(), name);
}

}  // namespace rupture::io
