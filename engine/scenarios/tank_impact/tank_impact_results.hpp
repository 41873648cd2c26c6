#pragma once
// The declared results of the tank-impact scenario (tank_impact_results.cpp): its summary scalars
// (plus those every SPH run reports) and its /series columns, SI units (docs/tank-impact.md).
#include "rupture/result_fields.hpp"

namespace rupture {

const ResultFields& tankImpactSummaryFields();
const ResultFields& tankImpactSeriesFields();

}  // namespace rupture
