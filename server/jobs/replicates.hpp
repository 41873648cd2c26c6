#pragma once
// Replicates: every sweep point runs on N samples. The request's
//   "replicates": {"count": N, "vary": "sample.seed"}
// names an integer field of the scenario's schema; replicate r (0..N-1) of a point sets it to
// base + r, where base is the point's own value (from the inputs, or the schema's default). Replicate 0
// is therefore the run the job would make without replicates. Runs of a point are consecutive:
// run index = point * N + r.
#include <functional>
#include <string>
#include <vector>

#include "common/problem.hpp"
#include "jobs/sweep.hpp"

namespace rupture::server {

/// At most this many replicates per sweep point (the server's --max-runs still bounds the job).
inline constexpr int kMaxReplicates = 100;

struct ReplicatePlan {
  int count = 1;     ///< 1 = no replicates
  std::string vary;  ///< the integer spec field varied; empty when count is 1 and nothing was asked
  bool requested() const { return !vary.empty(); }
  Json toJson() const { return requested() ? Json{{"count", count}, {"vary", vary}} : Json(); }
};

/// Reads the request's "replicates" member (null or absent: no replicates). Throws ApiError(400)
/// naming replicates.count or replicates.vary, the value and what is allowed: count an integer in
/// [1, kMaxReplicates], vary an integer field of the scenario's schema that is not swept.
ReplicatePlan parseReplicatePlan(const Json* member, const std::string& scenario, const SweepPlan& sweep);

struct ReplicatedPoint {
  SweepPoint point;   ///< spec with the varied field set
  int replicate = 0;  ///< 0..count-1
};

/// Makes a point's replicates: N copies, the varied field set to base + r.
class ReplicateExpander {
public:
  ReplicateExpander(const ReplicatePlan& plan, const std::string& scenario);
  /// Hands each replicate of `point` to `visit`, in replicate order (the point itself without
  /// replicates). Throws ApiError(400) naming replicates.vary when the point has no base value
  /// (not in the inputs, no schema default).
  void expand(SweepPoint&& point, const std::function<void(ReplicatedPoint&&)>& visit) const;

private:
  ReplicatePlan m_plan;
  nlohmann::json m_default;  ///< the varied field's schema default (null: none)
  std::vector<std::string> m_segments;
};

/// Each point N times (ReplicateExpander, for every point at once).
std::vector<ReplicatedPoint> expandReplicates(std::vector<SweepPoint> points, const ReplicatePlan& plan,
                                              const std::string& scenario);

/// The JSON Schema node of a dotted spec path (through "properties" and "items"), or nullptr.
const nlohmann::json* schemaNodeAt(const nlohmann::json& schema, const std::string& path);

/// True when a schema node declares "type": "integer" (or a type list holding it).
bool isIntegerSchema(const nlohmann::json& node);

}  // namespace rupture::server
