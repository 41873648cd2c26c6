#pragma once
// A number as messages and errors quote it: the shortest stream text ("1e+06", "0.0003").
#include <sstream>
#include <string>

namespace rupture {

inline std::string formatNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace rupture
