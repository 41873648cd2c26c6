#include <charconv>
#include <iostream>

#include "cli/cli.hpp"

namespace rupture::cli {

int usageError(const std::string& message) {
  std::cerr << "rupture: " << message << "\n";
  return 2;
}

int readFileArguments(const Args& args, const std::string& command, const std::string& usage, std::string& input,
                      std::string& output, bool& force) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--force") {
      force = true;
    } else if (args[i] == "-o" || args[i] == "--output") {
      if (i + 1 >= args.size()) return usageError(command + ": -o needs a file name");
      output = args[++i];
    } else if (!args[i].empty() && args[i][0] == '-') {
      return usageError(command + ": unknown option '" + args[i] + "'; " + usage);
    } else if (input.empty()) {
      input = args[i];
    } else {
      return usageError(command + ": " + usage);
    }
  }
  return 0;
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
