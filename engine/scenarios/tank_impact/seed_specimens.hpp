#pragma once
// The specimens of seed 002's campaign (Caleyron et al. 2013, Table 4) and what the seed measured on
// each: `specimen` in a tank-impact spec sets the plate and the impact speed of that test, and the
// run's summary carries the seed's numbers beside ours (docs/tank-impact.md#the-campaign). Every
// value cites the seed's section; NaN (null in the summary) where the seed gives none.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rupture {

struct SeedSpecimen {
  std::string name;            ///< Table 4's code: "E14A5", "FUA2", …
  /// The spec the specimen stands for: plate thickness and pre-crack, impact speed, and the plate
  /// spacing where the pre-crack needs a finer one (F14E3A5's 3 mm cracks).
  nlohmann::json spec;
  // What the seed reports (SI; NaN when it does not).
  double firstPeakLow = 0, firstPeakHigh = 0;  ///< Pa, measured range of the first peak (§3.1.1)
  double jetSpeed = 0;          ///< m/s, estimated from the film (§5.1)
  double simulatedJetSpeed = 0; ///< m/s, the seed's own simulation (§5.1)
  double tongueAngle = 0;       ///< rad, measured opening of the U tongue (§5.2)
  double timeToFracture = 0;    ///< s, measured from the pressure signal's drop (§5.3.2)
  std::string outcome;          ///< the specimen's final state (§3.2)
};

const std::vector<SeedSpecimen>& seedSpecimens();
/// nullptr when no specimen has that name.
const SeedSpecimen* findSeedSpecimen(const std::string& name);
std::vector<std::string> seedSpecimenNames();

}  // namespace rupture
