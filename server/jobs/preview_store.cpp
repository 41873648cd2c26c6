#include "jobs/preview_store.hpp"

#include <cstdio>
#include <random>

namespace rupture::server {

std::string PreviewStore::put(const std::string& scenario, std::string bytes, const std::string& mediaType) {
  static thread_local std::random_device entropy;
  char name[33];
  for (int word = 0; word < 4; ++word) std::snprintf(name + 8 * word, 9, "%08x", static_cast<unsigned>(entropy()));
  std::lock_guard lock(m_mutex);
  m_bytes += bytes.size();
  m_entries.push_back({name, scenario, {std::move(bytes), mediaType}});
  while (m_entries.size() > 1 && (m_entries.size() > m_maxPictures || m_bytes > m_maxBytes)) {
    m_bytes -= m_entries.front().picture.bytes.size();
    m_entries.pop_front();
  }
  return name;
}

std::optional<PreviewStore::Picture> PreviewStore::get(const std::string& scenario, const std::string& name) const {
  std::lock_guard lock(m_mutex);
  for (const Entry& e : m_entries)
    if (e.name == name && e.scenario == scenario) return e.picture;
  return std::nullopt;
}

}  // namespace rupture::server
