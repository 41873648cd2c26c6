#include "render/snapshot_field.hpp"

#include <algorithm>
#include <cmath>

namespace rupture::render {
namespace {

bool holds(const io::Hdf5File& file, const std::string& group, const char* dataset) {
  return file.exists(group + "/" + dataset);
}

/// The field's value per particle from the snapshot's datasets.
std::vector<double> fieldValues(const io::Hdf5File& file, const std::string& group, const std::string& field,
                                std::size_t n) {
  if (field == "damage" || field == "pressure" || field == "density") return file.readDatasetDouble(group + "/" + field);
  std::vector<double> out(n);
  if (field == "speed") {
    const std::vector<double> v = file.readDatasetDouble(group + "/velocity");
    for (std::size_t k = 0; k < n; ++k) out[k] = std::hypot(v[3 * k], v[3 * k + 1], v[3 * k + 2]);
    return out;
  }
  const std::vector<double> s = file.readDatasetDouble(group + "/stress");  // {n, 3, 3}
  for (std::size_t k = 0; k < n; ++k) {
    const double* t = &s[9 * k];
    if (field == "stress_xx") {
      out[k] = t[0];
    } else {  // von Mises equivalent of the symmetric part
      const double xx = t[0], yy = t[4], zz = t[8];
      const double xy = 0.5 * (t[1] + t[3]), yz = 0.5 * (t[5] + t[7]), zx = 0.5 * (t[2] + t[6]);
      out[k] = std::sqrt(0.5 * ((xx - yy) * (xx - yy) + (yy - zz) * (yy - zz) + (zz - xx) * (zz - xx)) +
                         3 * (xy * xy + yz * yz + zx * zx));
    }
  }
  return out;
}

const char* datasetOf(const std::string& field) {
  if (field == "speed") return "velocity";
  if (field == "stress_xx" || field == "von_mises") return "stress";
  return nullptr;
}

std::optional<double> numberAttribute(const io::Hdf5File& file, const std::string& path, const std::string& name) {
  if (!file.exists(path) || !file.hasAttribute(path, name)) return std::nullopt;
  try {
    return file.readAttributeDouble(path, name);
  } catch (const std::exception&) {  // a string where a number was expected: treated as absent
    return std::nullopt;
  }
}

}  // namespace

const std::vector<FieldDeclaration>& fieldDeclarations() {
  static const std::vector<FieldDeclaration> fields = {
      {"damage", "Damage", "1"},         {"von_mises", "Von Mises stress", "Pa"},
      {"stress_xx", "Stress xx", "Pa"},  {"pressure", "Pressure", "Pa"},
      {"speed", "Speed", "m/s"},         {"density", "Density", "kg/m^3"}};
  return fields;
}

const FieldDeclaration* findFieldDeclaration(const std::string& name) {
  for (const FieldDeclaration& f : fieldDeclarations())
    if (name == f.name) return &f;
  return nullptr;
}

std::vector<SnapshotRef> listSnapshots(const io::Hdf5File& file, const std::string& root) {
  const std::string base = root + "/snapshots";
  std::vector<SnapshotRef> out;
  if (!file.exists(base)) return out;
  for (const std::string& name : file.listGroup(base)) {
    const std::string group = base + "/" + name;
    if (!file.exists(group + "/position")) continue;
    SnapshotRef ref;
    ref.group = group;
    ref.time = numberAttribute(file, group, "time").value_or(std::nan(""));
    ref.strain = numberAttribute(file, group, "strain");
    out.push_back(std::move(ref));
  }
  // A strain of 0 on every snapshot is the XDMF layout's placeholder (impact imposes none), not a
  // strain: the pictures and pages do not say "strain 0".
  if (std::all_of(out.begin(), out.end(), [](const SnapshotRef& r) { return !r.strain || *r.strain == 0; }))
    for (SnapshotRef& r : out) r.strain.reset();
  return out;
}

std::vector<std::string> fieldsOf(const io::Hdf5File& file, const std::string& group) {
  std::vector<std::string> out;
  for (const FieldDeclaration& f : fieldDeclarations()) {
    const char* dataset = datasetOf(f.name);
    if (holds(file, group, dataset ? dataset : f.name)) out.push_back(f.name);
  }
  return out;
}

SnapshotField readSnapshotField(const io::Hdf5File& file, const std::string& root, const SnapshotRef& snapshot,
                                const std::string& field) {
  const std::vector<std::string> available = fieldsOf(file, snapshot.group);
  if (std::find(available.begin(), available.end(), field) == available.end()) {
    std::string allowed;
    for (const std::string& name : available) allowed += (allowed.empty() ? "" : ", ") + name;
    throw FieldImageError("field", "field '" + field + "' is not recorded in this run's snapshots; allowed: " +
                                       (allowed.empty() ? "none" : allowed));
  }
  SnapshotField out;
  const std::vector<double> x = file.readDatasetDouble(snapshot.group + "/position");
  const std::size_t n = x.size() / 3;
  out.position.resize(n);
  for (std::size_t k = 0; k < n; ++k) out.position[k] = {x[3 * k], x[3 * k + 1], x[3 * k + 2]};
  out.value = fieldValues(file, snapshot.group, field, n);
  if (out.value.size() != n) throw std::runtime_error("snapshot " + snapshot.group + ": '" + field + "' has " +
                                                      std::to_string(out.value.size()) + " values for " +
                                                      std::to_string(n) + " particles");
  if (holds(file, snapshot.group, "body")) {
    const std::vector<std::int64_t> body = file.readDatasetInt(snapshot.group + "/body");
    out.body.assign(body.begin(), body.end());
  }
  const std::string geometry = root + "/geometry";
  if (auto plate = numberAttribute(file, geometry, "plate_body")) out.plateBody = static_cast<int>(*plate);
  if (file.exists(geometry) && file.hasAttribute(geometry, "vertical_axis")) {
    try {
      const std::string axis = file.readAttributeString(geometry, "vertical_axis");
      if (axis == "x" || axis == "y" || axis == "z") out.verticalAxis = axis[0] - 'x';
    } catch (const std::exception&) {  // an index instead of a name
      if (auto a = numberAttribute(file, geometry, "vertical_axis")) out.verticalAxis = static_cast<int>(*a);
    }
  }

  // Disc sizes: the recorded radius (bonded models), else the particle spacing of the geometry
  // (SPH: fluid and walls; the plate's own spacing for its nodes), else from the points' extent.
  if (holds(file, snapshot.group, "radius")) {
    out.radius = file.readDatasetDouble(snapshot.group + "/radius");
  } else {
    const std::optional<double> spacing = numberAttribute(file, geometry, "spacing");
    const std::optional<double> plateSpacing = numberAttribute(file, geometry, "plate_spacing");
    double fallback = 0;
    if (!spacing) {
      std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
      for (const auto& p : out.position)
        for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
      std::array<double, 3> extent{};
      for (int a = 0; a < 3; ++a) extent[a] = n ? hi[a] - lo[a] : 0;
      std::sort(extent.begin(), extent.end());
      const double area = std::max(extent[1] * extent[2], 1e-300);
      fallback = n ? 0.5 * std::sqrt(area / static_cast<double>(n)) : 0;
    }
    out.radius.assign(n, spacing ? 0.5 * *spacing : fallback);
    if (plateSpacing && out.plateBody && out.body.size() == n)
      for (std::size_t k = 0; k < n; ++k)
        if (out.body[k] == *out.plateBody) out.radius[k] = 0.5 * *plateSpacing;
  }

  const std::string pairs = root + "/sample/bonds";
  if (file.exists(pairs) && holds(file, snapshot.group, "bond_intact")) {
    const std::vector<std::int64_t> ends = file.readDatasetInt(pairs);
    const std::vector<std::int64_t> intact = file.readDatasetInt(snapshot.group + "/bond_intact");
    const std::size_t bonds = std::min(ends.size() / 2, intact.size());
    for (std::size_t b = 0; b < bonds; ++b) {
      const auto i = ends[2 * b], j = ends[2 * b + 1];
      if (i < 0 || j < 0 || static_cast<std::size_t>(i) >= n || static_cast<std::size_t>(j) >= n) continue;
      (intact[b] ? out.intactBonds : out.brokenBonds)
          .push_back({static_cast<std::size_t>(i), static_cast<std::size_t>(j)});
    }
  }
  return out;
}

FieldValues readFieldValues(const io::Hdf5File& file, const SnapshotRef& snapshot, const std::string& field) {
  FieldValues out;
  const char* dataset = datasetOf(field);
  if (!holds(file, snapshot.group, dataset ? dataset : field.c_str())) return out;
  const std::vector<std::size_t> dims = file.datasetDims(snapshot.group + "/position");
  const std::size_t n = dims.empty() ? 0 : dims.front();
  out.value = fieldValues(file, snapshot.group, field, n);
  if (holds(file, snapshot.group, "body")) {
    const std::vector<std::int64_t> body = file.readDatasetInt(snapshot.group + "/body");
    out.body.assign(body.begin(), body.end());
  }
  return out;
}

}  // namespace rupture::render
