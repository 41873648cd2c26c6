#include "io/json_attributes.hpp"

#include <cstdint>
#include <limits>

namespace rupture::io {

void writeJsonAttributes(Hdf5File& file, const std::string& group, const nlohmann::json& values,
                         const std::map<std::string, std::string>& units) {
  file.createGroup(group);
  for (const auto& [name, v] : values.items()) {
    if (v.is_boolean()) file.setAttribute(group, name, std::int64_t{v.get<bool>() ? 1 : 0});
    else if (v.is_number_integer()) file.setAttribute(group, name, v.get<std::int64_t>());
    else if (v.is_number()) file.setAttribute(group, name, v.get<double>());
    else if (v.is_string()) file.setAttribute(group, name, v.get<std::string>());
    else if (v.is_null()) file.setAttribute(group, name, std::numeric_limits<double>::quiet_NaN());
    else file.setAttribute(group, name, v.dump());
    if (auto u = units.find(name); u != units.end()) file.setAttribute(group, name + "_unit", u->second);
  }
}

}  // namespace rupture::io
