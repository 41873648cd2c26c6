#pragma once
// What the dynamic-tension loop reads after every step to apply its stop rules: the strain, the
// two faces' stresses and the bonds that broke. On one process, from the system itself. On several
// ranks (distributed/subdomain.hpp), from one gather of the owned face elements' x-loads, the
// probe element's x and each rank's count of the bonds that broke whose end i it owns (and its
// cancel flag, for a loop that has no other collective to stop by): each face's
// load is added over its elements in index order, the one-process sum, so the numbers are the
// one-process numbers bit for bit.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "bonded/bonded_system.hpp"
#include "distributed/subdomain.hpp"
#include "scenarios/dynamic_tension/tension_loading.hpp"

namespace rupture {

struct TensionStep {
  double strain = 0;            ///< ε (1)
  FaceStresses stress;          ///< σ_Xmin, σ_Xmax, σ̄ (Pa)
  std::size_t brokenBonds = 0;  ///< in the last step, in the whole sample
  bool cancelled = false;       ///< the cancel was asked on some rank (on every rank at this step)
};

class TensionStepObservables {
public:
  /// part: the sub-domain this rank steps, or nullptr on one process. Both must outlive this.
  /// Collective on several ranks (each rank's record count, gathered once).
  TensionStepObservables(const TensionLoading& loading, const Subdomain* part);

  /// After a step of `stepped` (the whole system, or part's). Collective on several ranks.
  /// cancelHere: this rank's cancel flag, carried by the same gather, so that a cancel that reaches
  /// the ranks at different moments stops them all at the same step.
  TensionStep measure(const BondedSystem& stepped, bool cancelHere = false) const;

private:
  const TensionLoading& m_loading;
  const Subdomain* m_part;
  std::vector<std::int32_t> m_facesHere, m_facesWhole;  // owned face elements: local, whole-sample indices
  std::vector<double> m_faceOf;                         // 0: X_min, 1: X_max
  std::int32_t m_probeHere = -1;                        // local index of the probe when owned here
  std::vector<int> m_recordCounts;                      // doubles each rank gathers a step (fixed)
};

}  // namespace rupture
