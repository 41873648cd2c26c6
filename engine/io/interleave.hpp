#pragma once
// Structure-of-arrays fields to the row-major {n, 3} layout of HDF5 datasets.
#include <vector>

namespace rupture::io {

inline std::vector<double> interleave(const std::vector<double>& a, const std::vector<double>& b,
                                      const std::vector<double>& c) {
  std::vector<double> out(3 * a.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    out[3 * k] = a[k];
    out[3 * k + 1] = b[k];
    out[3 * k + 2] = c[k];
  }
  return out;
}

}  // namespace rupture::io
