#pragma once
// The declared results of the SPH scenarios (fluid_results.cpp): the scalars every fluid run
// reports (finishFluidRun) plus each scenario's own, and their /series columns. Extensive
// quantities of a 2-D run are per metre of depth (ResultField::unit2d).
#include "rupture/result_fields.hpp"

namespace rupture {

/// The scalars finishFluidRun adds to every SPH run's summary, after the scenario's own.
ResultFields withFluidCommonSummary(ResultFields own);

const ResultFields& damBreakSummaryFields();
const ResultFields& damBreakSeriesFields();
const ResultFields& pistonColumnSummaryFields();
const ResultFields& pistonColumnSeriesFields();

}  // namespace rupture
