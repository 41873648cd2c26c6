#pragma once
// One field of one snapshot of a run file, read for a picture: particle positions and sizes, the
// field's value per particle, the body of each particle (SPH runs) and the bonds (bonded runs),
// from the layout every scenario writes (/snapshots/<k>: position, velocity, and per model
// damage, stress, radius, pressure, density, body, bond_intact; /sample/bonds; /geometry).
#include <array>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/hdf5_file.hpp"

namespace rupture::render {

/// A request member that cannot be honoured: `member` names it ("field", "snapshot", ...),
/// `what()` says the value and what is allowed.
class FieldImageError : public std::invalid_argument {
public:
  FieldImageError(std::string member, const std::string& message)
      : std::invalid_argument(message), m_member(std::move(member)) {}
  const std::string& member() const { return m_member; }

private:
  std::string m_member;
};

/// A field a picture can show: its name in requests, a label for people and its SI unit.
struct FieldDeclaration {
  const char* name;
  const char* label;
  const char* unit;
};

/// damage, von_mises, stress_xx, speed, pressure, density: in this order, the first a snapshot has
/// is a picture's default (pressure before speed: an SPH run's default is its pressure).
const std::vector<FieldDeclaration>& fieldDeclarations();
const FieldDeclaration* findFieldDeclaration(const std::string& name);

struct SnapshotRef {
  std::string group;             ///< full path, e.g. "/run-2/snapshots/000003"
  double time = 0;               ///< s
  std::optional<double> strain;  ///< (1), tension runs; none when every snapshot says 0 (impact's placeholder)
};

/// The snapshots under root + "/snapshots", in order; empty when there are none.
std::vector<SnapshotRef> listSnapshots(const io::Hdf5File& file, const std::string& root);

/// The names of the declared fields this snapshot holds, in declaration order.
std::vector<std::string> fieldsOf(const io::Hdf5File& file, const std::string& snapshotGroup);

struct SnapshotField {
  std::vector<std::array<double, 3>> position;  ///< m
  std::vector<double> radius;                   ///< m, the drawn disc
  std::vector<double> value;                    ///< in the field's unit
  std::vector<int> body;                        ///< −1 fluid, else body index; empty: no bodies
  std::vector<std::array<std::size_t, 2>> brokenBonds, intactBonds;
  std::optional<int> plateBody;                 ///< the tank's plate, from /geometry plate_body
  std::optional<int> verticalAxis;              ///< 0, 1, 2 from /geometry vertical_axis
};

/// Reads `field` (a declared name the snapshot holds, else FieldImageError naming "field") with
/// the positions, sizes, bodies and, when the run has bonds, the bond pairs split by their state.
SnapshotField readSnapshotField(const io::Hdf5File& file, const std::string& root, const SnapshotRef& snapshot,
                                const std::string& field);

/// The field's values and the particles' bodies at one snapshot, without positions, sizes or
/// bonds: what the colour range over every snapshot of a run reads. Empty values when the
/// snapshot does not hold the field.
struct FieldValues {
  std::vector<double> value;
  std::vector<int> body;  ///< empty: no bodies
};
FieldValues readFieldValues(const io::Hdf5File& file, const SnapshotRef& snapshot, const std::string& field);

}  // namespace rupture::render
