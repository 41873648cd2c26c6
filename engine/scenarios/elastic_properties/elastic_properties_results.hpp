#pragma once
// The declared results of scenario "elastic-properties" (elastic_properties_results.cpp).
#include "rupture/result_fields.hpp"

namespace rupture {

const ResultFields& elasticPropertiesSummaryFields();

}  // namespace rupture
