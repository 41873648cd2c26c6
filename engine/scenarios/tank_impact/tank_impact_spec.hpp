#pragma once
// The tank-impact scenario's spec (Caleyron et al. 2013 §2): a water column in the steel cylinder (inner
// diameter D, rigid wall), closed at the bottom by the AU4G plate clamped on the rim of its Ø D spot
// face (SPH shell), hit through the piston by the carriage (mass M, initial speed V; the piston
// elastic, rigid, or one body with the carriage: fsi/impactor_column.hpp). The plate has a thickness, and optionally a central hole and pre-cracks (U, X, I, radial).
// Contract: api/schemas/tank-impact.schema.json, docs/tank-impact.md. SI units.
//
// Frame: the tank axis is z; the plate's mid-surface is the plane z = 0 (its reference frame is
// the shell's: x, y in the plane, normal +z); the water fills t/2 <= z <= t/2 + water_height,
// from the plate's upper face (t its thickness) to the piston; the jet leaves downwards (z < 0).
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fsi/contact_method.hpp"  // ContactMethod (engine/fsi owns it: the contact code selects on it)
#include "scenarios/fluid/impactor_spec.hpp"   // ImpactorSpec: the carriage, the piston and their contact
#include "sph/fluid_spec.hpp"
#include "shell/shell_parameters.hpp"

namespace rupture {

/// What is cut into the plate before the impact (seed §2, Table of tests).
enum class PrecrackShape {
  None,          ///< intact plate
  Hole,          ///< central hole of diameter `hole_diameter` (E14, E20 tests)
  U,             ///< U-shaped through-crack: two parallel arms of `length` joined by a base of `width` (FU tests)
  X,             ///< two crossed through-cracks of `length` each, centred (FX tests)
  I,             ///< one straight through-crack of `length`, centred (FI tests)
  HoleAndCracks  ///< central hole with `crack_count` radial cracks of `length` from its edge (TF tests)
};

struct PrecrackSpec {
  PrecrackShape shape = PrecrackShape::None;
  double holeDiameter = 0.0;  ///< m (hole, hole+cracks)
  double length = 0.0;        ///< m: U arm, X/I crack, radial crack from the hole edge
  double width = 0.0;         ///< m: U base (distance between the arms)
  int crackCount = 2;         ///< radial cracks (hole+cracks), evenly spaced
};

/// The thick bottom around the spot face ("Calculation 2" of the seed, §5.1, `plate.clamp:
/// "bottom"`, the default): the block's full thickness from the spot face's rim out to where it is
/// held. `plate.clamp: "rim"` ("Calculation 1"): the spot face alone, clamped at its rim.
struct PlateBottomSpec {
  double thickness = 0.025;      ///< the block's thickness (m): seed §2.2, 200 × 200 × 25 mm
  /// Where the block is held (m): by default 1.75 spot-face diameters, 140 mm for the seed's 80 mm,
  /// an assumption (the seed gives no screw circle).
  double clampDiameter = 0.14;
  /// Node spacing (m) within two plate spacings of the step, graded to plate.spacing beyond (the
  /// seed's finer elements where the plate tears, §5.3.1); 0 or plate.spacing: no refinement (the
  /// parser resolves the default to plate.spacing).
  double stepSpacing = 0.0;
};

/// The default clamp diameter over the spot face's (140 mm / 80 mm).
inline constexpr double kClampDiameterRatio = 1.75;

struct PlateSpec {
  std::string materialPreset = "au4g_2024_t351_seed";  ///< seed Tables 1 and 6 (material_presets.hpp)
  ShellParameters shell;      ///< thickness, density, material, damage law, layers … (preset, then overrides)
  double diameter = 0.08;     ///< clamped spot-face diameter (m); defaults to the tank's inner diameter
  double spacing = 0.0;       ///< node spacing Δ (m); default: the fluid spacing
  PrecrackSpec precrack;
  std::optional<PlateBottomSpec> bottom;  ///< the step to the thick bottom and its clamp; empty: clamped at the rim
};

struct ContactSpec {
  ContactMethod method = ContactMethod::Pinball;
};

struct TankImpactSpec {
  std::string description;
  /// A seed specimen (Table 4: "E14A5", …; seed_specimens.hpp) whose plate and speed the spec
  /// starts from, and whose measurements the summary reports beside ours; empty: none.
  std::string specimen;
  double innerDiameter = 0.08;   ///< D (m)
  double waterHeight = 0.180;    ///< H (m); default 0.205 − plate thickness (seed: H = 205 mm − e_p)
  io::ResolutionSpec resolution; ///< fluid spacing dx, h/dx, wall layers
  io::FluidSpec fluid;
  double soundSpeed = 1450.0;    ///< c0 resolved (m/s)
  double gravity = 9.81;         ///< m/s² along −z
  fsi::ImpactorSpec impactor;
  PlateSpec plate;
  ContactSpec contact;
  /// Pressure gauge position (m). Default: the seed's sensor on the cylinder's underside, read in
  /// the water next to the wall: r = R − 5 mm (x axis), 10 mm above the plate's upper face (at
  /// most H/2 above it): z = t/2 + min(10 mm, H/2).
  std::array<double, 3> gauge{0.035, 0.0, 0.011};
  std::vector<std::array<double, 3>> probes;   ///< further pressure probes (m)
  io::FluidRunSpec run;
  double estimatedParticles = 0;  ///< fluid, wall and plate particles the run will hold
};

/// Throws SpecError naming the field, its value and what is allowed.
TankImpactSpec parseTankImpactSpec(const nlohmann::json& json);
/// The resolved spec (every default filled in) for the result file.
nlohmann::json toJson(const TankImpactSpec& spec);
std::string toString(PrecrackShape shape);  ///< "none", "hole", "U", "X", "I", "hole+cracks"
std::string toString(ContactMethod method); ///< "pinball", "master_slave"

}  // namespace rupture
