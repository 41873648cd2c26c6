#include "cli/spec_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>

#include "io/json_text.hpp"

namespace rupture::cli {

int readSpecFile(const std::string& path, nlohmann::json& spec) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::cerr << "rupture: cannot read spec file '" << path << "': " << std::strerror(errno) << "\n";
    return 2;
  }
  std::stringstream text;
  text << in.rdbuf();
  try {
    spec = io::parseJsonText(text.str());
  } catch (const SpecError& e) {
    return reportSpecError(path, e);
  } catch (const nlohmann::json::exception& e) {
    std::cerr << path << ": not valid JSON: " << e.what() << "\n";
    return 2;
  }
  return 0;
}

int reportSpecError(const std::string& path, const SpecError& e) {
  std::cerr << path << ": " << e.what() << "\n";
  return 2;
}

}  // namespace rupture::cli
