#pragma once
// The preview pictures a dry run drew, kept in memory for the page to fetch by URL
// (GET /processes/{id}/previews/{picture}): the page's Content-Security-Policy admits images from
// the server only, and a picture is megapixels the JSON answer should not carry. Each is named by
// 128 random bits, so one client cannot guess another's; the oldest go first beyond `maxPictures`
// pictures or `maxBytes` bytes in all, and nothing survives a restart (a preview is asked again).
#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>
#include <string>

namespace rupture::server {

class PreviewStore {
public:
  explicit PreviewStore(std::size_t maxPictures = 32, std::size_t maxBytes = 64u << 20)
      : m_maxPictures(maxPictures), m_maxBytes(maxBytes) {}

  /// Keeps `bytes` (of `mediaType`) for `scenario`; returns its name (32 hex digits).
  std::string put(const std::string& scenario, std::string bytes, const std::string& mediaType);

  struct Picture {
    std::string bytes, mediaType;
  };
  /// The picture of that name drawn for that scenario, if still kept.
  std::optional<Picture> get(const std::string& scenario, const std::string& name) const;

  std::size_t maxPictures() const { return m_maxPictures; }

private:
  struct Entry {
    std::string name, scenario;
    Picture picture;
  };
  mutable std::mutex m_mutex;
  std::deque<Entry> m_entries;  // oldest first
  std::size_t m_bytes = 0;
  const std::size_t m_maxPictures, m_maxBytes;
};

}  // namespace rupture::server
