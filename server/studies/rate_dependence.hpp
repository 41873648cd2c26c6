#pragma once
// Rate dependence of a strain-rate sweep: from the point means of the peak stress against the
// strain rate (one series per combination of the other swept values, e.g. per initial-velocity
// field), it reports
//   plateau        the low-rate plateau: starting at the lowest rate, the consecutive points whose
//                  mean is within kPlateauTolerance (10 %) of the lowest-rate mean; its value is the
//                  mean of every run in those points (Pa), its scatter their sample standard
//                  deviation (Pa) and that over the value (1);
//   doubling_rate  the rate (1/s) where the mean peak stress first reaches twice the plateau,
//                  interpolated linearly in log(rate)-log(stress) between the two points around it;
//                  null with a reason when no point reaches it;
//   slopes         d log10(stress) / d log10(rate) between neighbouring rates (1: "per decade"):
//                  about 0 quasi-static, 1/3 energy-limited, 1 inertial.
#include <string>
#include <vector>

#include "studies/replicate_statistics.hpp"

namespace rupture::server {

inline constexpr double kPlateauTolerance = 0.10;

/// The swept path that holds the strain rate: the first whose last segment is "strain_rate", or "".
std::string strainRatePath(const std::vector<std::string>& sweptPaths);

/// One series of (rate, values of the runs at that rate), rates > 0, any order.
struct RateSample {
  double rate = 0;
  std::vector<double> values;
};

/// The analysis of one series (see the file comment), as JSON with SI values.
Json rateDependenceSeries(std::vector<RateSample> samples);

/// The whole job's analysis for `quantity` (default peak_stress), or null when no swept path is a
/// strain rate. {"rate_path", "quantity", "plateau_tolerance", "units", "series": [{"group", ...}]}
Json rateDependence(const SummaryTable& table, const std::vector<PointAggregate>& points,
                    const std::string& quantity = "peak_stress");

}  // namespace rupture::server
