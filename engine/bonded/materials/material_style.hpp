#pragma once
// A bonded material style: everything the configuration layer knows about one value of
// material.model. The style reads and writes its parameter block (material.<name>), says how far
// its bonds reach on a lattice and which lattice pairs it keeps, installs its law, criterion and
// per-bond constants, and names its failure criteria. Spec parsing, sample building, the memory
// estimate, elastic-properties and the calibrate command ask the style (registry.hpp) instead of
// comparing model names. The hot loops never see a style: assign() picks a BondModel
// (bonded/bond_model.hpp) once, and the loop is templated on it.
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "bonded/sample_spec.hpp"
#include "io/spec_reader.hpp"
#include "lattice/lattice_geometry.hpp"

namespace rupture {

class BondedSystem;
struct BondStore;

/// What a style's parser may read beyond its own block: the sample as the spec gives it (read raw,
/// before the sample is validated) and the whole spec.
struct MaterialContext {
  LatticeKind lattice = LatticeKind::Random;
  int dimension = 2;
  const nlohmann::json& root;
};

/// A failure criterion a style offers: its name in "criterion", the key of its critical value in
/// the style's block, and that value's unit.
struct CriterionKey {
  std::string_view name, key, unit;
};

/// Bonds per site beyond the few nearest neighbours (peridynamic horizons hold tens to hundreds),
/// for the run's memory estimate, and the words that say where the count comes from.
struct LongRangeBonds {
  double perSite = 0;
  std::string basis;
};

/// A valid material block of the style on a 3D lattice (and that lattice): for the documentation
/// and the generic law suite, which runs every registered style.
struct MaterialExample {
  std::string lattice;
  nlohmann::json material;
};

class MaterialStyle {
 public:
  virtual ~MaterialStyle() = default;

  /// The value of material.model and the key of the style's parameter block.
  virtual std::string_view name() const = 0;
  /// The lattices the style runs on; empty: every sample, random packings included.
  virtual std::vector<LatticeKind> lattices() const { return {}; }
  /// The failure criteria the style offers, the default first.
  virtual std::vector<CriterionKey> criteria() const = 0;
  /// The criterion `m` chose (for the checks every style shares, such as material.interblock).
  virtual std::string criterion(const MaterialSpec& m) const = 0;

  /// Reads material.<name> into `m`, and the contact defaults that follow from it
  /// (m.contact.young_modulus, poisson_ratio). Errors name the field (SpecError).
  virtual void parse(const io::SpecReader& material, const MaterialContext& context, MaterialSpec& m) const = 0;
  /// The resolved block material.<name> (defaults filled in) for the result file.
  virtual nlohmann::json toJson(const MaterialSpec& m) const = 0;
  /// Bonds per site beyond the nearest neighbours (memory estimate); none by default.
  virtual LongRangeBonds longRangeBonds(const SampleSpec&, const MaterialSpec&) const { return {}; }

  /// The longest bond the style puts between lattice sites (m).
  virtual double bondReach(const SampleSpec& sample, const MaterialSpec& m) const = 0;
  /// Drops the lattice pairs within the reach that are not bonds of the style; keeps all by default.
  virtual void pruneLatticeBonds(const SampleSpec&, const MaterialSpec&, BondStore&) const {}
  /// Installs the law and criterion and sets every bond's constants (stiffness, threshold).
  virtual void assign(BondedSystem& system, const SampleSpec& sample, const MaterialSpec& m) const = 0;

  /// Whether the calibration (the fits to target properties and the strength test) works on it.
  virtual bool calibratable() const { return false; }
  virtual MaterialExample example() const = 0;
};

}  // namespace rupture
