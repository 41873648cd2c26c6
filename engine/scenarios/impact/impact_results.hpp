#pragma once
// The declared results of scenario "impact" (impact_results.cpp).
#include "rupture/result_fields.hpp"

namespace rupture {

const ResultFields& impactSummaryFields();
const ResultFields& impactSeriesFields();

}  // namespace rupture
