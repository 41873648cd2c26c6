#pragma once
// The declared results of the SPH scenarios (fluid_results.cpp): the scalars every fluid run
// reports (finishFluidRun) plus each scenario's own, and their /series columns. Extensive
// quantities of a 2-D run are per metre of depth (ResultField::unit2d).
#include <string>
#include <utility>
#include <vector>

#include "rupture/result_fields.hpp"

namespace rupture {

/// The /series columns a fluid recorder writes, in declaration order, with their units for the
/// dimension (the probe columns, named with '*', are added by the recorder).
std::vector<std::pair<std::string, std::string>> seriesColumns(const ResultFields& series, int dimension);

/// The scalars finishFluidRun adds to every SPH run's summary, after the scenario's own.
ResultFields withFluidCommonSummary(ResultFields own);

const ResultFields& damBreakSummaryFields();
const ResultFields& damBreakSeriesFields();
const ResultFields& pistonColumnSummaryFields();
const ResultFields& pistonColumnSeriesFields();

}  // namespace rupture
