// rupture plot RESULT.h5 -o OUT.png|svg|pdf [--field F] [--snapshot K | --time T] [--view xy|xz|yz]
//              [--body all|fluid|N] [--slice D] [--bonds broken|all|none] [--min V] [--max V]
//              [--width W] [--height H] [--run K] [--force]
// rupture plot RESULT.h5 --series Y[,Y...] [--x X] -o OUT.png|svg|pdf [--width W] [--height H] [--run K]
//
// The picture of a run's field at one snapshot (engine/render/field_image.hpp), or its time series
// as a line plot: the same image the server's run page shows, without a server. The format follows
// OUT's extension; OUT is written through a temporary name and never replaced without --force.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>

#include "cli/cli.hpp"
#include "io/hdf5_file.hpp"
#include "render/field_image.hpp"
#include "render/series_plot.hpp"
#include "rupture/quantity_text.hpp"

namespace rupture::cli {
namespace {

constexpr const char* kPlotUsage =
    "usage: rupture plot RESULT.h5 -o OUT.png|svg|pdf [options]\n"
    "  a field picture (the default):\n"
    "  --field F               damage, von_mises, stress_xx, pressure, speed or density (default: the\n"
    "                          first the run recorded, in this order)\n"
    "  --snapshot K            snapshot index from 0, negative from the end (default -1: the last)\n"
    "  --time T                the snapshot nearest T seconds (instead of --snapshot)\n"
    "  --view xy|xz|yz         the plane drawn (default: the section or plane that shows most)\n"
    "  --body all|fluid|N      which particles of an SPH run (default: the plate for damage, else fluid)\n"
    "  --slice D               only points within D metres of the middle of the depth axis\n"
    "  --bonds broken|all|none bonds drawn as lines (default: the broken ones in red, none for\n"
    "                          peridynamics, whose damage field shows its cracks)\n"
    "  --min V, --max V        the colour range, in the field's SI unit\n"
    "  --range run|snapshot    the default colour range: the field's over every snapshot of the run\n"
    "                          (run, the default: snapshots compare by colour) or this snapshot's\n"
    "  a series plot:\n"
    "  --series Y[,Y...]       plot these /series datasets (one unit) against --x\n"
    "  --x X                   the x series (default: strain when recorded, else time)\n"
    "  both:\n"
    "  --width W, --height H   size in px (pt for PDF), 48 to 4000 (default 800 x 600, series 800 x 500)\n"
    "  --run K                 the run inside a job's merged file (GET /jobs/{id}/results)\n"
    "  --force                 replace OUT if it exists\n";

bool writeAtomically(const std::string& path, const std::string& bytes) {
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      return false;
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (!ec) return true;
  std::error_code ignored;
  std::filesystem::remove(temporary, ignored);  // never a stray temporary beside the picture
  return false;
}

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (!item.empty()) out.push_back(item);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

}  // namespace

int plotCommand(const Args& args) {
  std::string input, output;
  std::map<std::string, std::string> values;
  bool force = false;
  static const std::vector<std::string> valued = {"-o",     "--output", "--field", "--snapshot", "--time",
                                                  "--view", "--body",   "--slice", "--bonds",    "--min",
                                                  "--max",  "--width",  "--height", "--run",     "--series",
                                                  "--x",    "--range"};
  for (std::size_t k = 0; k < args.size(); ++k) {
    const std::string& a = args[k];
    if (a == "--help" || a == "-h") {
      std::cout << kPlotUsage;
      return 0;
    }
    if (a == "--force") {
      force = true;
    } else if (std::find(valued.begin(), valued.end(), a) != valued.end()) {
      if (k + 1 >= args.size()) return usageError("plot: option " + a + " needs a value; see rupture plot --help");
      (a == "-o" || a == "--output" ? output : values[a]) = args[++k];
    } else if (!a.empty() && a[0] == '-') {
      return usageError("plot: unknown option '" + a + "'; see rupture plot --help");
    } else if (input.empty()) {
      input = a;
    } else {
      return usageError("plot: more than one result file; see rupture plot --help");
    }
  }
  if (input.empty()) return usageError("plot: missing RESULT.h5; see rupture plot --help");
  if (output.empty()) return usageError("plot: missing -o OUT.png|svg|pdf; see rupture plot --help");
  const std::string extension = std::filesystem::path(output).extension().string();
  render::ImageFormat format;
  if (extension == ".png") format = render::ImageFormat::Png;
  else if (extension == ".svg") format = render::ImageFormat::Svg;
  else if (extension == ".pdf") format = render::ImageFormat::Pdf;
  else return usageError("plot: -o '" + output + "': the extension names the format; allowed: .png, .svg, .pdf");
  std::error_code ec;
  if (!force && std::filesystem::exists(output, ec))
    return usageError("plot: '" + output + "' exists; pass --force to replace it, or name another -o");
  if (values.count("--series") && (values.count("--field") || values.count("--snapshot") || values.count("--time")))
    return usageError("plot: --series draws the time series; --field, --snapshot and --time are for a field picture");

  long long run = -1, width = 0, height = 0, snapshot = 0;
  double number = 0;
  if (values.count("--run") && !parseIntOption("--run", values["--run"], 0, 1000000, run)) return 2;
  if (values.count("--width") && !parseIntOption("--width", values["--width"], render::kMinImageSide, render::kMaxImageSide, width)) return 2;
  if (values.count("--height") && !parseIntOption("--height", values["--height"], render::kMinImageSide, render::kMaxImageSide, height)) return 2;

  io::Hdf5File file = [&] {
    try {
      return io::Hdf5File::openReadOnly(input);
    } catch (const std::exception& e) {
      throw std::runtime_error("cannot read '" + input + "': " + e.what());
    }
  }();
  std::string root;
  if (run >= 0) {
    root = "/run-" + std::to_string(run);
    if (!file.exists(root)) return usageError("plot: --run " + std::to_string(run) + ": '" + input + "' has no group " + root);
  } else if (!file.exists("/series") && !file.exists("/snapshots")) {
    std::string runs;
    for (const std::string& name : file.listGroup("/"))
      if (name.rfind("run-", 0) == 0) runs += (runs.empty() ? "" : ", ") + name.substr(4);
    if (!runs.empty()) return usageError("plot: '" + input + "' is a job's file with several runs: name one with --run K (" + runs + ")");
  }

  try {
    std::string bytes, what;
    if (values.count("--series")) {
      render::SeriesPlotRequest request;
      request.root = root;
      request.format = format;
      request.x = values["--x"];
      request.y = splitList(values["--series"]);
      if (width) request.width = static_cast<int>(width);
      if (height) request.height = static_cast<int>(height);
      const render::SeriesPlot plot = render::renderSeriesPlot(file, request);
      bytes = plot.bytes;
      for (const std::string& y : plot.y) what += (what.empty() ? "" : ", ") + y;
      what += " against " + plot.x;
    } else {
      render::FieldImageRequest request;
      request.root = root;
      request.format = format;
      request.field = values["--field"];
      request.view = values["--view"];
      request.body = values["--body"];
      if (values.count("--bonds")) request.bonds = values["--bonds"];
      if (values.count("--range")) request.range = values["--range"];
      if (values.count("--snapshot")) {
        if (!parseIntOption("--snapshot", values["--snapshot"], -1000000, 1000000, snapshot)) return 2;
        request.snapshot = static_cast<long>(snapshot);
      }
      for (const char* name : {"--time", "--slice", "--min", "--max"}) {
        if (!values.count(name)) continue;
        if (!parseDoubleOption(name, values[name], number)) return 2;
        (std::string(name) == "--time" ? request.time : std::string(name) == "--slice" ? request.slice
                                                      : std::string(name) == "--min"   ? request.min
                                                                                       : request.max) = number;
      }
      if (width) request.width = static_cast<int>(width);
      if (height) request.height = static_cast<int>(height);
      const render::FieldImage image = render::renderFieldImage(file, request);
      bytes = image.bytes;
      what = image.field + " at t = " + formatQuantity(image.time, "s") + " (snapshot " +
             std::to_string(image.snapshot) + " of 0 to " + std::to_string(image.snapshots - 1) + "), " +
             std::to_string(image.drawn) + " particles, colours " + formatQuantity(image.min, image.unit) + " to " +
             formatQuantity(image.max, image.unit) +
             (image.range == "run" ? " (over every snapshot)" : image.range == "snapshot" ? " (this snapshot)" : "");
    }
    if (!writeAtomically(output, bytes)) {
      std::cerr << "rupture plot: cannot write '" << output << "'\n";
      return 1;
    }
    std::cerr << "rupture plot: " << what << ": " << output << "\n";
  } catch (const render::FieldImageError& e) {
    const std::string option = e.member() == "series" || e.member() == "y" ? "--series" : "--" + e.member();
    return usageError("plot: " + option + ": " + e.what());
  }
  return 0;
}

}  // namespace rupture::cli
