// rupture: run, validate and inspect scenarios; calibrate beams; benchmark the engine.
#include <algorithm>
#include <iostream>
#include <optional>

#include "distributed/communicator.hpp"
#include "io/provenance.hpp"
#include "cli/cli.hpp"

namespace {

constexpr const char* kUsage = R"(usage: rupture <command> [options]

commands:
  run SPEC.json -o RUN.h5 [--threads N] [--progress-file FILE] [--json] [--force] [--resume]
      [--status-interval S] [--stop-at-step N]
                                          run a scenario, write one HDF5 file (+ .xdmf2 sidecar) and
                                          print its summary: a table, or with --json the JSON;
                                          --progress-file keeps FILE up to date with the progress as
                                          JSON; an existing RUN.h5 is replaced only with --force;
                                          --resume continues a run stopped by Ctrl-C or SIGTERM
                                          from RUN.h5.checkpoint (--stop-at-step N stops after step
                                          N with one); off a terminal, a status line
                                          every --status-interval S seconds (default 10) and a
                                          timing breakdown at the end (rupture run --help says more);
                                          under mpirun -np N, one impact or dynamic-tension
                                          run over N processes
  xdmf RESULT.h5 [-o OUT.xdmf2] [--force] write a ParaView sidecar for a run file, or one per run
                                          for a job's merged file (RESULT.run-<k>.xdmf2); an
                                          existing sidecar is replaced only with --force
  plot RESULT.h5 -o OUT.png|svg|pdf [--field F] [--snapshot K|--time T] [--view xy|xz|yz]
       [--body all|fluid|N] [--slice D] [--bonds broken|all|none] [--min V] [--max V] [--range run|snapshot]
       [--width W] [--height H] [--run K] [--force]
                                          a picture of a run's field at a snapshot (damage, stress,
                                          speed, pressure; broken bonds in red)
  plot RESULT.h5 --series Y[,Y...] [--x X] -o OUT.png|svg|pdf
                                          a run's time series (rupture plot --help says more)
  preview SPEC.json -o OUT.png|svg [--force]
                                          the discretised sample, plate or tank the run starts
                                          from, built by the run's own builders (no time step):
                                          its counts and sizes on stdout and in the picture
  validate SPEC.json [--max-run-steps N]  check a spec against its scenario (exit 2 if invalid),
                                          and its estimated time steps against N (default 100000000,
                                          as rupture-server's and rupture run's --max-run-steps)
  validate REQUEST.json [--scenario NAME] check a server request file (the body of
                                          POST /processes/NAME/execution): its inputs against NAME
  validate-suite [--quick|--full] [-o DIR] [--case ID]... [--threads N] [--list]
                                          run the published validation cases (validation/) and
                                          write the report: DIR/index.html, report.json,
                                          report.csv, figures/ (docs/validation.md); exit 1 when
                                          a quantity leaves its tolerance
  scenarios                               list the scenarios
  schema SCENARIO                         print a scenario's JSON Schema
  calibrate SPEC.json [--target-young-modulus E --target-poisson-ratio NU]
            [--target-tensile-strength S] [--threads N]
                                          measure macroscopic E, nu, tensile strength and onset
                                          strain, or fit the beams to the targets; JSON on stdout,
                                          progress on stderr
  bench W1 [--threads N] [--particles N] [--steps N] [--stiffness-weibull M]
  bench W2 [--threads N] [--steps N]
  bench W3 [--threads N] [--steps N]
  bench TANK [--threads N] [--steps N] [--spec FILE]
                                          tank-impact FXA5 (or FILE), fluid and shell timed apart
  bench TANK-SEED [--threads N] [--end-time s] [--subcycling on|off] [--step-estimate bound|spectral]
                                          the seed's TF14A5 at the seed's inputs, run whole
  bench STREAM [--threads N] [--megabytes M]
                                          memory bandwidth (copy, scale, add, triad over three
                                          arrays of M MiB), the loops' roofline
                                          run a benchmark, print one JSON line
  -o, --output FILE                       the output file of run and xdmf
  --help, -h                              this text (rupture run --help: run's options in full)
  --version                               the version

exit codes: 0 done, 1 failure, 2 invalid input, 130 interrupted (run: the file is kept, marked incomplete)
)";

}  // namespace

int main(int argc, char** argv) {
  using namespace rupture::cli;
  // Under mpirun or srun each process is one rank of a decomposed run (docs/distributed.md); a
  // program started alone never starts MPI.
  std::optional<rupture::MpiSession> mpi;
  try {
    if (rupture::MpiSession::launched()) mpi.emplace(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "rupture: " << e.what() << "\n";
    return 2;
  }
  Args args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    std::cout << kUsage;
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "--version") {
    const rupture::io::BuildInfo& build = rupture::io::buildInfo();
    std::cout << "rupture " << RUPTURE_VERSION << "\ncommit " << build.commit << "\ncompiler " << build.compiler
              << " (" << build.buildType << ": " << build.flags << ")\n";
    return 0;
  }
  const std::string command = args[0];
  const Args rest(args.begin() + 1, args.end());
  const bool wantsHelp = std::find_if(rest.begin(), rest.end(), [](const std::string& a) {
                           return a == "--help" || a == "-h";
                         }) != rest.end();
  if (wantsHelp && command != "run" && command != "plot") {  // run and plot have their own, longer help
    std::cout << kUsage;
    return 0;
  }
  if (command == "run") {
    // On several ranks a failure of one (a full disk under the first's file) would leave the
    // others waiting in a collective, and MPI_Finalize waiting for them: it ends the whole job.
    int code = 1;
    try {
      code = runCommand(rest);
    } catch (const std::exception& e) {
      std::cerr << "rupture run: " << e.what() << "\n";
    }
    if (code == 1) rupture::MpiSession::abortJob(code);
    return code;
  }
  try {
    if (command == "validate") return validateCommand(rest);
    if (command == "scenarios") return scenariosCommand(rest);
    if (command == "schema") return schemaCommand(rest);
    if (command == "calibrate") return calibrateCommand(rest);
    if (command == "bench") return benchCommand(rest);
    if (command == "xdmf") return xdmfCommand(rest);
    if (command == "plot") return plotCommand(rest);
    if (command == "preview") return previewCommand(rest);
    if (command == "validate-suite") return validateSuiteCommand(rest);
  } catch (const std::exception& e) {
    std::cerr << "rupture " << command << ": " << e.what() << "\n";
    return 1;
  }
  return usageError("unknown command '" + command + "'; see rupture --help");
}
