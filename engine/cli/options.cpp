#include <charconv>
#include <iostream>

#include "cli/cli.hpp"

namespace rupture::cli {

int usageError(const std::string& message) {
  std::cerr << "rupture: " << message << "\n";
  return 2;
}

bool parseIntOption(const std::string& name, const std::string& text, long long min, long long max,
                    long long& out) {
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, out);
  if (ec != std::errc() || ptr != end || out < min || out > max) {
    std::cerr << "rupture: option " << name << " = '" << text << "'; allowed: an integer in [" << min
              << ", " << max << "]\n";
    return false;
  }
  return true;
}

bool parseDoubleOption(const std::string& name, const std::string& text, double& out) {
  try {
    std::size_t used = 0;
    out = std::stod(text, &used);
    if (used == text.size()) return true;
  } catch (const std::exception&) {
  }
  std::cerr << "rupture: option " << name << " = '" << text << "'; allowed: a number\n";
  return false;
}

}  // namespace rupture::cli
