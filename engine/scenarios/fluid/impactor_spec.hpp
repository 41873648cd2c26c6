#pragma once
// The `impactor` object of the tank-impact and piston-column specs (schema part
// api/schemas/parts/impactor.schema.json, docs/tank-impact.md#impactor): the model, the carriage,
// the piston and their contact. SI units.
#include <nlohmann/json.hpp>

#include "fsi/impactor_column.hpp"
#include "io/spec_reader.hpp"

namespace rupture {

/// Reads `impactor` (path in its reader). bore: the tube's inner diameter, the piston's default
/// diameter (m); endTime: the run's length (s), to refuse a column that would take more than 1e9
/// point-steps. Throws SpecError naming the field, the value and what is allowed.
fsi::ImpactorSpec parseImpactor(const io::SpecReader& impactor, double bore, double endTime);
/// The impactor with every default filled in; a rigid one has no piston or contact.
nlohmann::json toJson(const fsi::ImpactorSpec& spec);

}  // namespace rupture
