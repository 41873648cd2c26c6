#pragma once
// Compares two HDF5 result files object by object: the same groups and datasets, every dataset's
// values bit for bit (numbers by their bytes as doubles, strings as text), every attribute equal.
// Names in `ignoredAttributes` are skipped wherever they appear (wall times, cache hits: what a
// run records about how it ran, not what it computed).
#include <hdf5.h>

#include <cstring>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "io/hdf5_file.hpp"

namespace rupture::testing {

namespace hdf5_compare_detail {

inline herr_t collect(hid_t, const char* name, const H5O_info_t* info, void* data) {
  auto* out = static_cast<std::map<std::string, H5O_type_t>*>(data);
  (*out)[std::string("/") + (std::strcmp(name, ".") == 0 ? "" : name)] = info->type;
  return 0;
}

/// Every object of the file: path -> group or dataset.
inline std::map<std::string, H5O_type_t> objects(const std::string& path) {
  std::map<std::string, H5O_type_t> out;
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) return out;
  H5Ovisit(file, H5_INDEX_NAME, H5_ITER_NATIVE, collect, &out);
  H5Fclose(file);
  return out;
}

inline bool isStringAttribute(const std::string& file, const std::string& obj, const std::string& name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t a = H5Aopen_by_name(f, obj.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  const hid_t t = H5Aget_type(a);
  const bool text = H5Tget_class(t) == H5T_STRING;
  H5Tclose(t), H5Aclose(a), H5Fclose(f);
  return text;
}

inline bool isStringDataset(const std::string& file, const std::string& obj) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = H5Dopen2(f, obj.c_str(), H5P_DEFAULT);
  const hid_t t = H5Dget_type(d);
  const bool text = H5Tget_class(t) == H5T_STRING;
  H5Tclose(t), H5Dclose(d), H5Fclose(f);
  return text;
}

inline bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

}  // namespace hdf5_compare_detail

/// What a run records about how it ran, not what it computed (docs/checkpoints.md): wall times,
/// cache hits, the resume record. The attributes a resumed run's file may differ in.
inline const std::set<std::string>& howARunRan() {
  static const std::set<std::string> names = {"wall_time_s",   "from_cache",       "sample_from_cache",
                                              "fluid_time_s",  "shell_time_s",     "contact_time_s",
                                              "shell_gradients_time_s", "shell_layers_time_s", "shell_forces_time_s",
                                              "shell_integration_time_s", "shell_fracture_time_s", "shell_spectrum_time_s",
                                              "checkpoint_resumes", "resumed_from_steps",
                                              "started_utc",   "finished_utc"};
  return names;
}

/// The differences between two files ("" when none): one line per differing object or attribute.
inline std::string hdf5Differences(const std::string& a, const std::string& b,
                                   const std::set<std::string>& ignoredAttributes) {
  using namespace hdf5_compare_detail;
  std::string out;
  const auto objectsA = objects(a), objectsB = objects(b);
  if (objectsA.empty() || objectsB.empty()) return "cannot open " + (objectsA.empty() ? a : b) + "\n";
  const io::Hdf5File fa = io::Hdf5File::openReadOnly(a), fb = io::Hdf5File::openReadOnly(b);
  for (const auto& [path, type] : objectsA) {
    auto other = objectsB.find(path);
    if (other == objectsB.end()) { out += path + ": only in the first file\n"; continue; }
    if (other->second != type) { out += path + ": of another kind\n"; continue; }
    if (type == H5O_TYPE_DATASET) {
      if (isStringDataset(a, path)) {
        if (fa.readDatasetString(path) != fb.readDatasetString(path)) out += path + ": text differs\n";
      } else {
        if (fa.datasetDims(path) != fb.datasetDims(path)) out += path + ": shape differs\n";
        else if (!sameBits(fa.readDatasetDouble(path), fb.readDatasetDouble(path))) out += path + ": values differ\n";
      }
    }
    const auto attributesA = fa.listAttributes(path), attributesB = fb.listAttributes(path);
    std::set<std::string> names(attributesA.begin(), attributesA.end());
    names.insert(attributesB.begin(), attributesB.end());
    for (const std::string& name : names) {
      if (ignoredAttributes.count(name)) continue;
      if (!fa.hasAttribute(path, name) || !fb.hasAttribute(path, name)) {
        out += path + "@" + name + ": only in one file\n";
        continue;
      }
      if (isStringAttribute(a, path, name) != isStringAttribute(b, path, name)) {
        out += path + "@" + name + ": of another type\n";
      } else if (isStringAttribute(a, path, name)) {
        if (fa.readAttributeString(path, name) != fb.readAttributeString(path, name))
          out += path + "@" + name + ": \"" + fa.readAttributeString(path, name) + "\" vs \"" +
                 fb.readAttributeString(path, name) + "\"\n";
      } else if (!sameBits({fa.readAttributeDouble(path, name)}, {fb.readAttributeDouble(path, name)})) {
        out += path + "@" + name + ": " + std::to_string(fa.readAttributeDouble(path, name)) + " vs " +
               std::to_string(fb.readAttributeDouble(path, name)) + "\n";
      }
    }
  }
  for (const auto& [path, type] : objectsB)
    if (!objectsA.count(path)) out += path + ": only in the second file\n";
  return out;
}

}  // namespace rupture::testing
