#pragma once
// Scenario "dynamic-tension": uniaxial dynamic tension of a porous brittle bonded sample at a
// prescribed strain rate, with one of three initial velocity fields (V0, VL, VH), after
// V. Longchamp, J. Girardot, D. André, F. Malaise, I. Iordanoff, "Analyse numérique de
// l'endommagement dynamique à l'échelle de la microstructure par simulation discrète",
// CSMA 2024, hal-04610894, section 3 (eqs. 3–9).
//
// One run: build the sample → (VH, or V0 without a ramp time: the cached preliminary run) →
// initial velocity field → velocity-Verlet steps with the X_max face velocity imposed → stop once
// no path of intact bonds joins X_min to X_max and no bond broke for run.settle_round_trips wave
// round trips, or at run.max_strain / run.max_steps / on cancel (or, if run.stop_fraction is set,
// once σ̄ < stop_fraction × peak) → macroscopic fragments, debris, cracks across the section.
// Output: one HDF5 file (tension_recorder.hpp), summary scalars in RunOutcome::summary.
// Documentation: docs/dynamic-tension.md; spec: api/schemas/dynamic-tension.schema.json.
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "rupture/run.hpp"
#include "scenarios/dynamic_tension/dynamic_tension_spec.hpp"
#include "scenarios/scenario.hpp"

namespace rupture {

/// The registry entry (declared in scenarios/registry.cpp).
Scenario dynamicTensionScenario();

/// Runs a parsed spec; `json` is the spec as given, recorded in the file.
RunOutcome runDynamicTension(const DynamicTensionSpec& spec, const nlohmann::json& json, const std::string& resultPath,
                             RunControl& control);


}  // namespace rupture
