#include "views/preview_picture.hpp"

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "render/sample_picture.hpp"
#include "rupture/quantity_text.hpp"
#include "rupture/sample_preview.hpp"

namespace rupture::server {

namespace {

Json unavailable(const std::string& reason, Json more = Json::object()) {
  Json doc{{"available", false}, {"reason", reason}};
  doc.update(more);
  return doc;
}

/// Sets `cancel` once `seconds` have passed or `stopping` is set, until it is destroyed.
class Deadline {
public:
  Deadline(double seconds, std::atomic<bool>& cancel, const std::atomic<bool>& stopping)
      : m_thread([this, seconds, &cancel, &stopping] {
          const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
          std::unique_lock lock(m_mutex);
          // Short waits, so that a stopping server is heard within a tenth of a second.
          while (!m_done && std::chrono::steady_clock::now() < end && !stopping.load())
            m_wake.wait_for(lock, std::chrono::milliseconds(100));
          if (!m_done) cancel.store(true);
        }) {}
  ~Deadline() {
    {
      std::lock_guard lock(m_mutex);
      m_done = true;
    }
    m_wake.notify_all();
    m_thread.join();
  }
  Deadline(const Deadline&) = delete;
  Deadline& operator=(const Deadline&) = delete;

private:
  std::mutex m_mutex;
  std::condition_variable m_wake;
  bool m_done = false;
  std::thread m_thread;  // last: it starts once the members above exist
};

Json limitsOf(const PicturePolicy& policy) {
  return {{"max_elements", policy.maxElements},
          {"max_memory_bytes", policy.maxMemoryBytes},
          {"max_seconds", policy.maxSeconds}};
}

}  // namespace

std::optional<Json> pictureRefusal(const rupture::RunEstimate& estimate, const PicturePolicy& policy) {
  const Json limits = limitsOf(policy);
  if (estimate.particles > policy.maxElements)
    return unavailable("the run holds an estimated " + formatQuantity(std::round(estimate.particles), "1") +
                            " elements or particles (set by " + estimate.field + "); a preview picture is built for at most " +
                            formatQuantity(policy.maxElements, "1") +
                            ": building it would cost what the run's first stage costs. Coarsen " + estimate.field +
                            " to see the picture, or submit without one",
                       {{"limits", limits}, {"elements_estimated", std::llround(estimate.particles)}});
  if (estimate.memoryBytes > policy.maxMemoryBytes)
    return unavailable("the run needs an estimated " + formatQuantity(estimate.memoryBytes / 1048576.0, "1") +
                            " MiB; a preview picture is built for runs of at most " +
                            formatQuantity(policy.maxMemoryBytes / 1048576.0, "1") + " MiB",
                       {{"limits", limits}});
  return std::nullopt;
}

PreviewPicture previewPicture(const Json& spec, const rupture::RunEstimate& estimate, const PicturePolicy& policy,
                              const std::string& note, const std::string& cacheDirectory,
                              const std::atomic<bool>& stopping) {
  if (std::optional<Json> refused = pictureRefusal(estimate, policy)) return {std::move(*refused), {}};
  const Json limits = limitsOf(policy);
  std::atomic<bool> cancel{false};
  const auto started = std::chrono::steady_clock::now();
  PreviewPicture out;
  try {
    const Deadline deadline(policy.maxSeconds, cancel, stopping);
    const rupture::SamplePreview preview =
        rupture::buildSamplePreview(rupture::parseSpec(spec), cancel, cacheDirectory);
    render::SamplePictureRequest request;
    request.width = policy.width;
    request.height = policy.height;
    request.note = note;
    const render::SamplePicture picture =
        render::renderSamplePicture(preview, request, [&cancel] { return cancel.load(); });
    out.png = picture.bytes;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    out.doc = {{"available", true},
               {"media_type", picture.mediaType},
               {"width", policy.width},
               {"height", policy.height},
               {"elements", preview.elements},
               {"elements_name", preview.elementsName},
               {"bonds", preview.bonds > 0 ? Json(preview.bonds) : Json(nullptr)},
               {"plate_nodes", preview.plateNodes > 0 ? Json(preview.plateNodes) : Json(nullptr)},
               {"size_m", preview.dimension == 3 ? Json(preview.size) : Json::array({preview.size[0], preview.size[1]})},
               {"dimension", preview.dimension},
               {"groups", preview.groups},
               {"caption", preview.facts},
               {"note", note},
               {"sample_from_cache", preview.fromCache},
               {"build_s", seconds}};
  } catch (const rupture::PreviewNotAvailable& e) {
    out.doc = unavailable(e.what());
  } catch (const rupture::SpecError& e) {
    out.doc = unavailable(std::string("the spec cannot be built: ") + e.what());
  } catch (const std::runtime_error& e) {
    // Stopped by the bound (the builders' RunCancelled, the canvas's RenderStopped) or by a
    // stopping server: the flag says which, whatever the stage.
    if (cancel.load()) {
      out.doc = unavailable(stopping.load() ? "the server is stopping; ask again once it is back"
                                            : "building and drawing the sample took longer than the preview allows (" +
                                                  formatQuantity(policy.maxSeconds, "s") +
                                                  "); the run itself is not bounded by this",
                            {{"limits", limits}});
      return out;
    }
    // The builder's own refusal (a face without elements, pores that jam): the run would fail the same way.
    out.doc = unavailable(std::string("the sample cannot be built as specified (the run would fail the same way): ") +
                          e.what());
  }
  return out;
}

}  // namespace rupture::server
