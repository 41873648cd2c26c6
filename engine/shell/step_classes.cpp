#include "shell/step_classes.hpp"

#include <algorithm>
#include <cmath>

namespace rupture {
namespace {

/// The largest c ≤ coarsest with 2^c δ ≤ h (0 when even δ exceeds h: the plan's δ never does).
int classOf(double ownStep, double fineStep, int coarsest) {
  int c = 0;
  while (c < coarsest && std::ldexp(fineStep, c + 1) <= ownStep) ++c;
  return c;
}

/// Node indices sorted by class (counting sort, stable), and how many have a class ≤ c.
void sortByClass(const std::vector<std::uint8_t>& cls, std::vector<std::uint32_t>& order,
                 std::array<std::size_t, kMaxStepClass + 1>& upTo) {
  upTo.fill(0);
  for (std::uint8_t c : cls) ++upTo[c];
  for (int c = 1; c <= kMaxStepClass; ++c) upTo[c] += upTo[c - 1];
  std::array<std::size_t, kMaxStepClass + 1> next{};
  for (int c = 1; c <= kMaxStepClass; ++c) next[c] = upTo[c - 1];
  order.resize(cls.size());
  for (std::size_t i = 0; i < cls.size(); ++i) order[next[cls[i]]++] = static_cast<std::uint32_t>(i);
}

}  // namespace

SubcyclingPlan planSubcycling(const std::vector<double>& pointStep, double stableStep, double interval,
                              double multiRateStep) {
  SubcyclingPlan best;
  auto steps = [&](double h) { return std::max(1L, static_cast<long>(std::ceil(interval / h * (1.0 - 1e-12)))); };
  const long single = steps(stableStep);
  const long finest = multiRateStep > 0.0 ? steps(multiRateStep) : single;
  best.fineSteps = single;
  best.fineStep = interval / static_cast<double>(single);
  double bestCost = static_cast<double>(single) * static_cast<double>(pointStep.size());
  for (int C = 1; C <= kMaxStepClass && (1L << C) <= finest; ++C) {
    const long block = 1L << C;
    const long K = (finest + block - 1) / block * block;
    const double fine = interval / static_cast<double>(K);
    double cost = 0.0;
    for (double h : pointStep) cost += std::ldexp(static_cast<double>(K), -classOf(h, fine, C));
    if (cost < bestCost) {
      bestCost = cost;
      best = {K, C, fine};
    }
  }
  return best;
}

void ShellStepClasses::assignSingleRate(std::size_t n) {
  coarsest = 0;
  node.assign(n, 0);
  point.assign(n, 0);
  gather.assign(n, 0);
  sortByClass(point, pointOrder, pointsUpTo);
  sortByClass(gather, gatherOrder, gatherUpTo);
}

bool ShellStepClasses::assign(const std::vector<double>& nodeStep, const std::vector<double>& pointStep,
                              const SubcyclingPlan& plan, const std::vector<std::size_t>& offset,
                              const std::vector<std::size_t>& neighbour) {
  const std::size_t n = nodeStep.size();
  std::vector<std::uint8_t> nodes(n), points(n);
  for (std::size_t i = 0; i < n; ++i) {
    nodes[i] = static_cast<std::uint8_t>(classOf(nodeStep[i], plan.fineStep, plan.coarsest));
    points[i] = static_cast<std::uint8_t>(classOf(pointStep[i], plan.fineStep, plan.coarsest));
  }
  if (plan.coarsest == coarsest && nodes == node && points == point) return false;
  coarsest = plan.coarsest;
  node = std::move(nodes);
  point = std::move(points);
  // Node i's force takes the terms of the points whose kernels reach it (the kernels are
  // symmetric: j is i's neighbour when i is j's) and its hourglass pairs.
  gather.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint8_t c = std::min(point[i], node[i]);
    for (std::size_t p = offset[i]; p < offset[i + 1]; ++p) c = std::min({c, point[neighbour[p]], node[neighbour[p]]});
    gather[i] = c;
  }
  sortByClass(point, pointOrder, pointsUpTo);
  sortByClass(gather, gatherOrder, gatherUpTo);
  return true;
}

std::string pointsPerClass(const ShellStepClasses& classes) {
  std::string text;
  for (int c = 0; c <= kMaxStepClass; ++c) {
    const std::size_t count = classes.pointsUpTo[c] - (c > 0 ? classes.pointsUpTo[c - 1] : 0);
    if (count == 0) continue;
    if (!text.empty()) text += ", ";
    text += std::to_string(c) + ": " + std::to_string(count);
  }
  return text;
}

}  // namespace rupture
