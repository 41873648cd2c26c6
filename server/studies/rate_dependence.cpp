#include "studies/rate_dependence.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace rupture::server {

std::string strainRatePath(const std::vector<std::string>& sweptPaths) {
  for (const std::string& p : sweptPaths) {
    if (p == "strain_rate" || (p.size() > 12 && p.compare(p.size() - 12, 12, ".strain_rate") == 0)) return p;
  }
  return "";
}

Json rateDependenceSeries(std::vector<RateSample> samples) {
  Json doc = Json::object();
  samples.erase(std::remove_if(samples.begin(), samples.end(),
                               [](const RateSample& s) { return !(s.rate > 0) || s.values.empty(); }),
                samples.end());
  std::sort(samples.begin(), samples.end(), [](const RateSample& a, const RateSample& b) { return a.rate < b.rate; });
  doc["points"] = samples.size();
  if (samples.empty()) {
    doc["plateau"] = nullptr;
    doc["doubling_rate"] = nullptr;
    doc["doubling_reason"] = "no successful run reported the quantity at a positive rate";
    doc["slopes"] = Json::array();
    return doc;
  }
  std::vector<double> means;
  for (const RateSample& s : samples) {
    double sum = 0;
    for (double v : s.values) sum += v;
    means.push_back(sum / s.values.size());
  }
  // Plateau: from the lowest rate, the consecutive points within the tolerance of its mean.
  const double reference = means.front();
  std::size_t plateauEnd = 1;
  while (plateauEnd < samples.size() &&
         std::abs(means[plateauEnd] - reference) <= kPlateauTolerance * std::abs(reference)) {
    ++plateauEnd;
  }
  std::vector<double> plateauValues;
  for (std::size_t i = 0; i < plateauEnd; ++i) {
    plateauValues.insert(plateauValues.end(), samples[i].values.begin(), samples[i].values.end());
  }
  const ScalarStatistics plateau = describeSample(plateauValues);
  Json p = Json::object();
  p["value"] = plateau.mean;
  p["scatter_sd"] = plateau.sd ? Json(*plateau.sd) : Json();
  p["scatter_relative"] = plateau.sd && plateau.mean != 0 ? Json(*plateau.sd / std::abs(plateau.mean)) : Json();
  p["n_runs"] = plateau.n;
  p["n_points"] = plateauEnd;
  p["rate_range"] = Json::array({samples.front().rate, samples[plateauEnd - 1].rate});
  doc["plateau"] = p;

  // Doubling: the first point whose mean reaches twice the plateau, interpolated in log-log.
  const double target = 2 * plateau.mean;
  doc["doubling_rate"] = nullptr;
  if (!(plateau.mean > 0)) {
    doc["doubling_reason"] = "the plateau is not positive, so a log-log doubling is undefined";
  } else {
    bool found = false;
    for (std::size_t i = 1; i < samples.size() && !found; ++i) {
      if (means[i] < target) continue;
      found = true;
      const double la = std::log10(samples[i - 1].rate), lb = std::log10(samples[i].rate);
      if (means[i - 1] > 0 && means[i] > means[i - 1]) {
        const double fa = std::log10(means[i - 1]), fb = std::log10(means[i]);
        const double t = std::clamp((std::log10(target) - fa) / (fb - fa), 0.0, 1.0);
        doc["doubling_rate"] = std::pow(10.0, la + t * (lb - la));
      } else {
        doc["doubling_rate"] = samples[i].rate;
      }
      doc["doubling_between"] = Json::array({samples[i - 1].rate, samples[i].rate});
    }
    if (!found) {
      const auto top = std::max_element(means.begin(), means.end()) - means.begin();
      doc["doubling_reason"] = "not reached: the highest mean is " + formatNumber(means[top] / plateau.mean) +
                               " x the plateau (at rate " + formatNumber(samples[top].rate) +
                               " 1/s); sweep higher rates";
    }
  }
  Json slopes = Json::array();
  for (std::size_t i = 1; i < samples.size(); ++i) {
    Json s = Json::object();
    s["from"] = samples[i - 1].rate;
    s["to"] = samples[i].rate;
    if (means[i - 1] > 0 && means[i] > 0) {
      s["slope"] = (std::log10(means[i]) - std::log10(means[i - 1])) /
                   (std::log10(samples[i].rate) - std::log10(samples[i - 1].rate));
    } else {
      s["slope"] = nullptr;
      s["reason"] = "a mean is not positive";
    }
    slopes.push_back(std::move(s));
  }
  doc["slopes"] = slopes;
  return doc;
}

Json rateDependence(const SummaryTable& table, const std::vector<PointAggregate>& points, const std::string& quantity) {
  const std::string ratePath = strainRatePath(table.sweptPaths);
  if (ratePath.empty()) return Json();
  const std::size_t rateAxis =
      std::find(table.sweptPaths.begin(), table.sweptPaths.end(), ratePath) - table.sweptPaths.begin();
  Json doc = Json::object();
  doc["rate_path"] = ratePath;
  doc["quantity"] = quantity;
  doc["plateau_tolerance"] = kPlateauTolerance;
  doc["units"] = {{"rate", "1/s"},
                  {"plateau.value", "Pa"},
                  {"plateau.scatter_sd", "Pa"},
                  {"plateau.scatter_relative", "1"},
                  {"doubling_rate", "1/s"},
                  {"slopes.slope", "1"}};
  std::vector<std::string> order;
  std::map<std::string, std::pair<Json, std::vector<RateSample>>> groups;
  for (const PointAggregate& p : points) {
    Json group = Json::object();
    for (std::size_t a = 0; a < table.sweptPaths.size(); ++a) {
      if (a != rateAxis) group[table.sweptPaths[a]] = a < p.swept.size() ? p.swept[a] : Json();
    }
    const std::string key = group.dump();
    if (!groups.count(key)) {
      order.push_back(key);
      groups[key].first = group;
    }
    const Json rate = rateAxis < p.swept.size() ? p.swept[rateAxis] : Json();
    const std::vector<double>* values = p.valuesOf(quantity);
    if (!rate.is_number() || !values || values->empty()) continue;
    groups[key].second.push_back({rate.get<double>(), *values});
  }
  Json series = Json::array();
  for (const std::string& key : order) {
    Json s = rateDependenceSeries(groups[key].second);
    Json entry = Json::object();
    entry["group"] = groups[key].first;
    for (auto& [k, v] : s.items()) entry[k] = v;
    series.push_back(std::move(entry));
  }
  doc["series"] = series;
  return doc;
}

}  // namespace rupture::server
