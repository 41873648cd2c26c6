#include "validation/case_runner.hpp"

#include <atomic>
#include <chrono>
#include <filesystem>
#include <thread>

#include "io/hdf5_file.hpp"

namespace rupture::validation {

namespace fs = std::filesystem;

namespace {

/// Passes the case's cancel and checkpoint-on-cancel on to the member run under way, and its
/// progress and status (for the status line) back, every 50 ms.
class ControlRelay {
public:
  ControlRelay(RunControl& outer, RunControl& inner, double done, double total)
      : m_thread([&outer, &inner, done, total, this] {
          while (!m_stop.load()) {
            if (outer.cancel.load()) {
              inner.checkpointOnCancel.store(false);
              inner.cancel.store(true);
            }
            const double fraction = (done + inner.progress.load()) / total;
            if (fraction > outer.progress.load()) outer.progress.store(fraction);
            outer.status.publish(inner.status.latest());
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
          }
        }) {}
  ~ControlRelay() {
    m_stop.store(true);
    m_thread.join();
  }
  ControlRelay(const ControlRelay&) = delete;
  ControlRelay& operator=(const ControlRelay&) = delete;

private:
  std::atomic<bool> m_stop{false};
  std::thread m_thread;
};

}  // namespace

std::optional<CaseRunData> runCase(const ValidationCase& c, const std::string& level, const std::string& workDirectory,
                                   RunControl& control, int threads) {
  const auto specs = caseSpecs(c, level);
  double total = 0, done = 0;
  for (const auto& [name, members] : specs) total += static_cast<double>(members.size());
  fs::create_directories(workDirectory);
  struct RemoveAfter {
    std::string dir;
    ~RemoveAfter() {
      std::error_code ignored;
      fs::remove_all(dir, ignored);
    }
  } removeAfter{workDirectory};

  CaseRunData data;
  for (const auto& [name, members] : specs) {
    std::vector<RunData> results;
    for (std::size_t k = 0; k < members.size(); ++k) {
      if (control.cancel.load()) return std::nullopt;
      const std::string path = workDirectory + "/" + name + "-" + std::to_string(k) + ".h5";
      if (control.log) {
        std::string message = c.id + ": run " + name;
        if (members.size() > 1) message.append(" ").append(std::to_string(k + 1)).append("/").append(std::to_string(members.size()));
        control.log(message);
      }
      RunControl inner;
      inner.cacheDirectory = control.cacheDirectory;
      inner.checkpointInterval = 0;  // a case is short, and restarts whole (docs/validation.md)
      RunOutcome outcome;
      {
        ControlRelay relay(control, inner, done, total);
        outcome = runSpec(members[k], path, inner, threads);
      }
      if (!outcome.completed) return std::nullopt;
      RunData run{outcome.summary, {}};
      {  // closed before the file is removed
        const io::Hdf5File file = io::Hdf5File::openReadOnly(path);
        for (const std::string& series : seriesNeeded(c, name))
          if (file.exists("/series/" + series)) run.series.emplace_back(series, file.readDatasetDouble("/series/" + series));
      }
      results.push_back(std::move(run));
      fs::remove(path);
      done += 1;
    }
    data.emplace_back(name, std::move(results));
  }
  return data;
}

}  // namespace rupture::validation
