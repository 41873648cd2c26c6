#include "jobs/job_preview.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "jobs/cost_model.hpp"

namespace rupture::server {

double queueMakespan(const std::vector<double>& seconds, int workers, const std::vector<int>& slots) {
  std::vector<double> freeAt(static_cast<std::size_t>(std::max(workers, 1)), 0.0);  // when each worker comes free
  double lastStart = 0, end = 0;
  for (std::size_t k = 0; k < seconds.size(); ++k) {
    // The scheduler starts only the head of the queue, once as many workers as it has ranks are
    // free (it holds no more than the server has), so a run never starts before the one ahead of it.
    const int taken = std::clamp(k < slots.size() ? slots[k] : 1, 1, static_cast<int>(freeAt.size()));
    std::sort(freeAt.begin(), freeAt.end());
    const double start = std::max(lastStart, freeAt[static_cast<std::size_t>(taken - 1)]);
    for (int w = 0; w < taken; ++w) freeAt[static_cast<std::size_t>(w)] = start + seconds[k];
    lastStart = start;
    end = std::max(end, start + seconds[k]);
  }
  return end;
}

Json jobPreview(const std::string& scenario, const NewJob& job, const std::vector<RunForecast>& forecasts,
                const PreviewContext& where) {
  const int threads = where.threadsPerRun;
  const int workers = where.workers;
  Json runs = Json::array();
  double elementsMin = 0, elementsMax = 0, elementsTotal = 0, memoryMax = 0, stepsMax = 0;
  std::vector<double> seconds;
  std::vector<int> slots;  // the workers each run holds: its ranks
  bool timed = !forecasts.empty();
  std::string sizeField, memoryBasis, stepsBasis;
  for (std::size_t k = 0; k < forecasts.size(); ++k) {
    const RunForecast& f = forecasts[k];
    const rupture::RunEstimate& e = f.estimate;
    Json swept = Json::object();
    for (std::size_t a = 0; a < job.sweptPaths.size() && a < f.swept.size(); ++a)
      swept[job.sweptPaths[a].get<std::string>()] = f.swept[a];
    const std::optional<double> s = estimatedRunSeconds(scenario, e, threads);
    timed = timed && s.has_value();
    if (s) {
      seconds.push_back(*s);
      slots.push_back(e.ranks);
    }
    auto estimateOrNull = [](double v) { return v > 0 && std::isfinite(v) ? Json(v) : Json(nullptr); };
    runs.push_back({{"index", k},
                    {"swept", swept},
                    {"replicate", f.replicate},
                    {"elements", e.particles > 0 ? Json(std::llround(e.particles)) : Json(nullptr)},
                    {"memory_bytes", e.memoryBytes > 0 ? Json(std::llround(e.memoryBytes)) : Json(nullptr)},
                    {"ranks", e.ranks},
                    {"steps", e.steps > 0 && std::isfinite(e.steps) ? Json(std::llround(e.steps)) : Json(nullptr)},
                    {"time_step_s", estimateOrNull(e.timeStep)},
                    {"estimated_run_s", s ? Json(*s) : Json(nullptr)}});
    elementsMin = k == 0 ? e.particles : std::min(elementsMin, e.particles);
    elementsMax = std::max(elementsMax, e.particles);
    elementsTotal += e.particles;
    memoryMax = std::max(memoryMax, e.memoryBytes);
    if (std::isfinite(e.steps)) stepsMax = std::max(stepsMax, e.steps);
    if (sizeField.empty()) sizeField = e.field, memoryBasis = e.basis, stepsBasis = e.stepsBasis;
  }
  auto countOrNull = [](double v) { return v > 0 ? Json(std::llround(v)) : Json(nullptr); };
  Json doc;
  doc["dry_run"] = true;
  doc["processID"] = scenario;
  if (!job.name.empty()) doc["name"] = job.name;
  doc["runs"] = forecasts.size();
  int replicates = 1;
  for (int r : job.replicates) replicates = std::max(replicates, r + 1);
  doc["replicates"] = replicates;
  doc["sweep_points"] = forecasts.size() / static_cast<std::size_t>(replicates);
  doc["elements"] = {{"min", countOrNull(elementsMin)}, {"max", countOrNull(elementsMax)},
                     {"total", countOrNull(elementsTotal)}, {"set_by", sizeField}};
  doc["memory_bytes"] = countOrNull(memoryMax);  // the largest run's, as admission checks each run
  doc["max_run_memory_bytes"] = std::isfinite(where.maxRunMemory) ? Json(std::llround(where.maxRunMemory)) : Json(nullptr);
  doc["memory_basis"] = memoryBasis;
  doc["steps"] = countOrNull(stepsMax);
  doc["steps_basis"] = stepsBasis;
  const CostModel* model = costModelFor(scenario);
  if (timed) {
    double total = 0;
    for (double s : seconds) total += s;
    doc["estimated_run_s"] = *std::max_element(seconds.begin(), seconds.end());  // the longest run
    doc["estimated_total_s"] = total;  // every run one after the other
    // Local workers take the queue first come, first served; on a cluster every run may start at once.
    // With Slurm each run gets its ranks' tasks, so the longest run is the job's time.
    doc["estimated_wall_s"] = workers > 0 ? queueMakespan(seconds, workers, slots) : doc["estimated_run_s"].get<double>();
  } else {
    doc["estimated_run_s"] = doc["estimated_total_s"] = doc["estimated_wall_s"] = nullptr;
  }
  doc["cost_model"] = model ? Json{{"seconds_per_element_step", model->secondsPerElementStep > 0
                                                                     ? Json(model->secondsPerElementStep)
                                                                     : Json(nullptr)},
                                   {"seconds_per_element", model->secondsPerElement > 0 ? Json(model->secondsPerElement)
                                                                                         : Json(nullptr)},
                                   {"threads_per_run", threads},
                                   {"workers", workers > 0 ? Json(workers) : Json(nullptr)},
                                   {"basis", model->basis},
                                   {"uncertainty", model->uncertainty}}
                            : Json(nullptr);
  // The queue as it stands: the job is checked against its bounds, but a full queue does not refuse
  // a preview (the real POST answers 503 then).
  const int queued = where.queuedRuns;
  doc["queue"] = {{"queued_runs", queued},
                  {"max_queued_runs", where.maxQueuedRuns},
                  {"fits_now", static_cast<long long>(queued) + static_cast<long long>(forecasts.size()) <=
                                   static_cast<long long>(where.maxQueuedRuns)}};
  // The sample is counted from its spec, not built: building and drawing it costs the run's first
  // stage, so it is done only when asked (picture=true, the form's Preview button).
  doc["picture"] = {{"available", false},
                    {"reason", "not asked: add picture=true to build the first run's sample, plate or tank and "
                               "draw it"}};
  doc["run_estimates"] = std::move(runs);
  return doc;
}

}  // namespace rupture::server
