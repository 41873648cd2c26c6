#pragma once
// Scalar JSON values as HDF5 attributes of a group, each with a "<name>_unit" string attribute
// beside it when its unit is known: booleans as int64 0/1, integers as int64, numbers as double,
// null as NaN, strings as strings, anything else as its JSON text.
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "io/hdf5_file.hpp"

namespace rupture::io {

void writeJsonAttributes(Hdf5File& file, const std::string& group, const nlohmann::json& values,
                         const std::map<std::string, std::string>& units);

}  // namespace rupture::io
