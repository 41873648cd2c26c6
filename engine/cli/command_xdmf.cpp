// rupture xdmf: a ParaView sidecar for any result file, a run file or a job's merged file (one
// sidecar per run inside it), e.g. one downloaded from the server.
#include <filesystem>
#include <iostream>

#include "cli/cli.hpp"
#include "io/hdf5_file.hpp"
#include "io/xdmf_writer.hpp"

namespace rupture::cli {

namespace fs = std::filesystem;

int xdmfCommand(const Args& args) {
  std::string input, output;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "-o" || args[i] == "--output") {
      if (i + 1 >= args.size()) return usageError("xdmf: -o needs a file name");
      output = args[++i];
    } else if (!args[i].empty() && args[i][0] == '-') {
      return usageError("xdmf: unknown option '" + args[i] + "'; usage: rupture xdmf RESULT.h5 [-o OUT.xdmf2]");
    } else if (input.empty()) {
      input = args[i];
    } else {
      return usageError("xdmf: usage: rupture xdmf RESULT.h5 [-o OUT.xdmf2]");
    }
  }
  if (input.empty()) return usageError("xdmf: usage: rupture xdmf RESULT.h5 [-o OUT.xdmf2]");
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
  for (const std::string& root : roots) {
    // ParaView 5.11 opens *.xdmf with its broken Xdmf3 readers; *.xdmf2 picks the working one.
    const std::string path = !output.empty() ? output
                             : root.empty()  ? stem.string() + ".xdmf2"
                                             : stem.string() + "." + root.substr(1) + ".xdmf2";
    io::writeXdmfSidecar(input, path, root);
    std::cout << path << "\n";
  }
  return 0;
}

}  // namespace rupture::cli
