#pragma once
// The `rupture` command line: one function per subcommand, each returning the process exit code
// (0 done, 1 failure, 2 invalid input).
#include <string>
#include <vector>

namespace rupture::cli {

using Args = std::vector<std::string>;

int runCommand(const Args& args);
int validateCommand(const Args& args);
int scenariosCommand(const Args& args);
int schemaCommand(const Args& args);
int calibrateCommand(const Args& args);
int benchCommand(const Args& args);
int xdmfCommand(const Args& args);
int plotCommand(const Args& args);
int previewCommand(const Args& args);
int validateSuiteCommand(const Args& args);

/// Exit code 2 with a message on stderr.
int usageError(const std::string& message);

/// Parses "--name value" options; returns false (and prints) on a bad number.
bool parseIntOption(const std::string& name, const std::string& text, long long min, long long max,
                    long long& out);
bool parseDoubleOption(const std::string& name, const std::string& text, double& out);

/// Reads the arguments of a command on one file, "INPUT [-o|--output OUT] [--force]" (xdmf,
/// preview); returns 0, or 2 after printing `usage` prefixed with the command's name.
int readFileArguments(const Args& args, const std::string& command, const std::string& usage, std::string& input,
                      std::string& output, bool& force);

}  // namespace rupture::cli
