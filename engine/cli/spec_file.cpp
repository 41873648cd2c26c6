#include "cli/spec_file.hpp"

#include <fstream>
#include <iostream>
#include <sstream>

namespace rupture::cli {

int readSpecFile(const std::string& path, nlohmann::json& spec) {
  std::ifstream in(path);
  if (!in) {
    std::cerr << "rupture: cannot read spec file '" << path << "'\n";
    return 2;
  }
  std::stringstream text;
  text << in.rdbuf();
  try {
    spec = nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::parse_error& e) {
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
