// A case's runs against its references: each quantity's value, how far off it is in units of its
// tolerance (the deviation: at most 1 passes), its verdict, and the figure's curves.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "validation/validation_case.hpp"

namespace rupture::validation {

namespace {

using Json = nlohmann::json;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// Points kept of a curve drawn in a figure (every k-th row beyond that).
constexpr std::size_t kMaxCurvePoints = 1500;

Json numberOrNull(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

const std::vector<RunData>* membersOf(const CaseRunData& data, const std::string& run) {
  for (const auto& [name, members] : data)
    if (name == run) return &members;
  return nullptr;
}

/// y(x) by linear interpolation; NaN outside the series.
double interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  const std::size_t n = std::min(xs.size(), ys.size());
  for (std::size_t k = 1; k < n; ++k) {
    const double x0 = xs[k - 1], x1 = xs[k];
    if ((x0 <= x && x <= x1) || (x1 <= x && x <= x0)) {
      const double t = x1 == x0 ? 0.0 : (x - x0) / (x1 - x0);
      return ys[k - 1] + t * (ys[k] - ys[k - 1]);
    }
  }
  return kNaN;
}

/// The first x at which y reaches `level`, interpolated between the rows that straddle it; NaN if
/// y never reaches it.
double firstReaching(const std::vector<double>& xs, const std::vector<double>& ys, double level) {
  const std::size_t n = std::min(xs.size(), ys.size());
  for (std::size_t k = 0; k < n; ++k) {
    if (!(ys[k] >= level)) continue;
    if (k == 0 || !std::isfinite(ys[k - 1])) return xs[k];
    const double t = (level - ys[k - 1]) / (ys[k] - ys[k - 1]);
    return xs[k - 1] + t * (xs[k] - xs[k - 1]);
  }
  return kNaN;
}

/// The source's value: the mean over the run's members (NaN if any member lacks it).
double valueOf(const ValueSource& s, std::optional<double> at, const CaseRunData& data) {
  const std::vector<RunData>* members = membersOf(data, s.run);
  if (!members || members->empty()) return kNaN;
  double sum = 0;
  for (const RunData& m : *members) {
    double v = kNaN;
    if (!s.summary.empty()) {
      auto it = m.summary.find(s.summary);
      if (it != m.summary.end() && it->is_number()) v = it->get<double>() * s.factor;
    } else if (const auto* xs = m.findSeries(s.seriesX)) {
      if (const auto* ys = m.findSeries(s.seriesY)) {
        std::vector<double> scaled(xs->size());
        std::transform(xs->begin(), xs->end(), scaled.begin(), [&](double x) { return x * s.xFactor; });
        if (s.maxOver) {
          for (std::size_t k = 0; k < std::min(scaled.size(), ys->size()); ++k)
            if (scaled[k] >= s.maxOver->first && scaled[k] <= s.maxOver->second && std::isfinite((*ys)[k]))
              v = std::isfinite(v) ? std::max(v, (*ys)[k] * s.factor) : (*ys)[k] * s.factor;
        } else if (s.firstReaching) {
          std::vector<double> y(ys->begin(), ys->end());
          for (double& value : y) value *= s.factor;
          v = firstReaching(scaled, y, *s.firstReaching);
        } else if (at) {
          v = interpolate(scaled, *ys, *at) * s.factor;
        }
      }
    }
    if (!std::isfinite(v)) return kNaN;
    sum += v;
  }
  const double mean = sum / static_cast<double>(members->size());
  if (!s.per) return mean;
  ValueSource denominator;
  denominator.run = s.per->first;
  denominator.summary = s.per->second;
  return mean / valueOf(denominator, std::nullopt, data);
}

struct Compared {
  double deviation, off;
};

/// How far `ours` is from the reference in units of the tolerance, and its signed relative
/// difference to the reference value (or to the bound it passes).
Compared compare(double ours, std::optional<double> value, std::optional<double> low, std::optional<double> high,
                 const Tolerance& tol) {
  if (!std::isfinite(ours)) return {kNaN, kNaN};
  auto against = [&](double ref) {
    const double allowed = tol.relative * std::fabs(ref) + tol.absolute;
    const double err = std::fabs(ours - ref);
    const double deviation = allowed > 0 ? err / allowed : (err == 0 ? 0.0 : std::numeric_limits<double>::infinity());
    return Compared{deviation, ref != 0 ? (ours - ref) / std::fabs(ref) : kNaN};
  };
  if (value) return against(*value);
  if (low && ours < *low) return against(*low);
  if (high && ours > *high) return against(*high);
  return {0.0, 0.0};
}

std::string verdictOf(bool passed, bool known) {
  if (passed) return known ? "unexpected pass" : "pass";
  return known ? "known failure" : "fail";
}

}  // namespace

const std::vector<double>* RunData::findSeries(const std::string& name) const {
  for (const auto& [n, values] : series)
    if (n == name) return &values;
  return nullptr;
}

std::vector<std::string> seriesNeeded(const ValidationCase& c, const std::string& run) {
  std::vector<std::string> out;
  auto add = [&](const std::string& name) {
    if (!name.empty() && std::find(out.begin(), out.end(), name) == out.end()) out.push_back(name);
  };
  for (const Quantity& q : c.quantities)
    if (q.ours.run == run) add(q.ours.seriesX), add(q.ours.seriesY);
  if (c.figure && c.figure->run == run) add(c.figure->x), add(c.figure->y);
  return out;
}

Json evaluateCase(const ValidationCase& c, const std::string& level, const CaseRunData& data) {
  const bool quick = level == "quick";
  Json quantities = Json::array();
  std::map<std::string, std::pair<double, double>> referenceBand;  // name -> (low, high), for the figure
  int passed = 0, failed = 0, known = 0, unexpected = 0;
  double worst = 0;
  for (const Quantity& q : c.quantities) {
    if (quick && !q.inQuick) continue;
    const double ours = valueOf(q.ours, q.at, data);
    std::optional<double> value = q.reference.value;
    if (q.reference.fromRun) value = valueOf(*q.reference.fromRun, std::nullopt, data);
    const Compared cmp = compare(ours, value, q.reference.low, q.reference.high, q.tolerance);
    const bool ok = std::isfinite(cmp.deviation) && cmp.deviation <= 1.0;
    const std::string verdict = verdictOf(ok, !q.knownFailure.empty());
    (verdict == "pass" ? passed : verdict == "fail" ? failed : verdict == "known failure" ? known : unexpected) += 1;
    worst = std::isfinite(cmp.deviation) ? std::max(worst, cmp.deviation) : std::numeric_limits<double>::infinity();
    Json reference = {{"uncertainty", q.reference.uncertainty}};
    if (value) reference["value"] = numberOrNull(*value);
    if (q.reference.low) reference["low"] = *q.reference.low;
    if (q.reference.high) reference["high"] = *q.reference.high;
    referenceBand[q.name] = value ? std::pair{*value, *value}
                                  : std::pair{q.reference.low.value_or(kNaN), q.reference.high.value_or(kNaN)};
    Json row = {{"name", q.name},
                {"label", q.label},
                {"unit", q.unit},
                {"ours", numberOrNull(ours)},
                {"reference", reference},
                {"tolerance", {{"relative", q.tolerance.relative}, {"absolute", q.tolerance.absolute}}},
                {"deviation", std::isinf(cmp.deviation) ? Json("inf") : numberOrNull(cmp.deviation)},
                {"off", numberOrNull(cmp.off)},
                {"verdict", verdict}};
    if (q.at) row["at"] = *q.at;
    if (!q.knownFailure.empty()) row["known_failure"] = q.knownFailure;
    quantities.push_back(std::move(row));
  }
  const std::string verdict = failed ? "fail" : unexpected ? "unexpected pass" : known ? "known failure" : "pass";
  Json result = {{"case", c.id},
                 {"title", c.title},
                 {"paper", c.paper},
                 {"citation", c.citation},
                 {"how_read", c.howRead},
                 {"comparison", c.comparison},
                 {"level", level},
                 {"quick_note", c.quickNote},
                 {"verdict", verdict},
                 {"counts", {{"pass", passed}, {"fail", failed}, {"known_failure", known}, {"unexpected_pass", unexpected}}},
                 {"worst_deviation", std::isinf(worst) ? Json("inf") : Json(worst)},
                 {"quantities", std::move(quantities)}};
  if (c.figure) {
    const CaseFigure& f = *c.figure;
    Json xs = Json::array(), ys = Json::array();
    if (const std::vector<RunData>* members = membersOf(data, f.run); members && !members->empty()) {
      const RunData& first = members->front();
      const std::vector<double>* x = first.findSeries(f.x);
      const std::vector<double>* y = first.findSeries(f.y);
      if (x && y) {
        const std::size_t n = std::min(x->size(), y->size());
        const std::size_t stride = std::max<std::size_t>(1, (n + kMaxCurvePoints - 1) / kMaxCurvePoints);
        for (std::size_t k = 0; k < n; k += stride)
          if (std::isfinite((*x)[k]) && std::isfinite((*y)[k])) xs.push_back((*x)[k] * f.xFactor), ys.push_back((*y)[k] * f.yFactor);
      }
    }
    // Reference lines: horizontal ones on y, vertical ones on x (scaled as the axis).
    auto linesOf = [&](const std::vector<std::string>& names, double scale) {
      Json lines = Json::array();
      for (const std::string& name : names) {
        auto it = referenceBand.find(name);
        if (it == referenceBand.end()) continue;  // a full-level quantity in a quick run
        std::string label;
        for (const Quantity& q : c.quantities)
          if (q.name == name) label = q.label;
        lines.push_back({{"label", label},
                         {"low", numberOrNull(it->second.first * scale)},
                         {"high", numberOrNull(it->second.second * scale)}});
      }
      return lines;
    };
    result["figure"] = {{"x_label", f.xLabel},
                        {"y_label", f.yLabel},
                        {"ours", {{"x", xs}, {"y", ys}}},
                        {"points", f.points},
                        {"points_label", f.pointsLabel},
                        {"lines", linesOf(f.lineQuantities, f.yFactor)},
                        {"vertical_lines", linesOf(f.verticalLineQuantities, f.xFactor)}};
  }
  return result;
}

}  // namespace rupture::validation
