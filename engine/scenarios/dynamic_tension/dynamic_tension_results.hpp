#pragma once
// The declared results of scenario "dynamic-tension" (dynamic_tension_results.cpp).
#include "rupture/result_fields.hpp"

namespace rupture {

const ResultFields& dynamicTensionSummaryFields();
const ResultFields& dynamicTensionSeriesFields();

}  // namespace rupture
