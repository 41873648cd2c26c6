// rupture xdmf: a ParaView sidecar for any result file, a run file or a job's merged file (one
// sidecar per run inside it), e.g. one downloaded from the server. An existing sidecar is replaced
// only with --force, as run and plot replace their outputs.
#include <filesystem>
#include <iostream>

#include "cli/cli.hpp"
#include "io/hdf5_file.hpp"
#include "io/xdmf_writer.hpp"

namespace rupture::cli {

namespace fs = std::filesystem;

namespace {
constexpr const char* kUsage = "usage: rupture xdmf RESULT.h5 [-o OUT.xdmf2] [--force]";
}

int xdmfCommand(const Args& args) {
  std::string input, output;
  bool force = false;
  if (int code = readFileArguments(args, "xdmf", kUsage, input, output, force)) return code;
  if (input.empty()) return usageError(std::string("xdmf: ") + kUsage);
  std::error_code ec;
  if (!fs::is_regular_file(input, ec)) {
    return usageError("xdmf: cannot read '" + input + "': " +
                      (ec ? ec.message() : std::string(fs::exists(input) ? "not a regular file" : "no such file")));
  }
  std::vector<std::string> roots;
  try {
    roots = io::runGroupsWithSnapshots(input);
  } catch (const io::Hdf5Error& e) {
    return usageError("xdmf: '" + input + "' is not a readable HDF5 result file: " + e.what());
  }
  if (roots.empty()) {
    return usageError("xdmf: '" + input + "' holds no snapshots (neither /snapshots nor /run-<k>/snapshots)");
  }
  const fs::path stem = fs::path(input).replace_extension();
  if (!output.empty() && roots.size() > 1) {
    return usageError("xdmf: '" + input + "' holds " + std::to_string(roots.size()) +
                      " runs; leave out -o (one sidecar per run is written beside it)");
  }
  std::vector<std::string> paths;
  for (const std::string& root : roots) {
    // ParaView 5.11 opens *.xdmf with its broken Xdmf3 readers; *.xdmf2 picks the working one.
    paths.push_back(!output.empty() ? output
                    : root.empty()  ? stem.string() + ".xdmf2"
                                    : stem.string() + "." + root.substr(1) + ".xdmf2");
    // All or nothing: every sidecar is checked before the first is written.
    if (!force && fs::exists(paths.back(), ec))
      return usageError("xdmf: '" + paths.back() + "' exists; pass --force to replace it" +
                        (roots.size() == 1 ? ", or name another -o" : ""));
  }
  for (std::size_t k = 0; k < roots.size(); ++k) {
    io::writeXdmfSidecar(input, paths[k], roots[k]);
    std::cout << paths[k] << "\n";
  }
  return 0;
}

}  // namespace rupture::cli
