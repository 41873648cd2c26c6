#pragma once
// A case's picture as SVG text: our curve over the published points (with their uncertainty bars)
// and the reference levels as dashed lines or bands; or, for a case compared on scalars only, each
// quantity's signed deviation in units of its tolerance against the band [-1, 1] that passes.
#include <string>

#include <nlohmann/json.hpp>

namespace rupture::validation {

/// `result`: a case result (evaluateCase's layout). Never empty: a case without data says so.
std::string comparisonFigureSvg(const nlohmann::json& result);

}  // namespace rupture::validation
