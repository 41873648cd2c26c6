#pragma once
// Reading a spec file for the CLI, with exit code 2 and a clear message for every input problem.
#include <string>

#include <nlohmann/json.hpp>

#include "rupture/spec_error.hpp"

namespace rupture::cli {

/// Reads and parses a JSON file; returns 0, or 2 after printing why it cannot.
int readSpecFile(const std::string& path, nlohmann::json& spec);

/// Prints "PATH: invalid spec: field ... = ...; allowed: ..." and returns 2.
int reportSpecError(const std::string& path, const SpecError& e);

}  // namespace rupture::cli
