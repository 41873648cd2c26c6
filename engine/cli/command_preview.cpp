// rupture preview: the picture of a spec's discretisation, built as its run starts (the same
// builders, rupture::buildSamplePreview) and stopped before the first step; the server's dry run
// draws the same picture (docs/server.md, "Preview and cost"). An existing picture is replaced only
// with --force, as run and plot replace their outputs.
#include <atomic>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "cli/cli.hpp"
#include "cli/spec_file.hpp"
#include "render/sample_picture.hpp"
#include "rupture/sample_preview.hpp"

namespace rupture::cli {

namespace fs = std::filesystem;

namespace {
constexpr const char* kUsage = "usage: rupture preview SPEC.json -o OUT.png|svg [--force]";
}

int previewCommand(const Args& args) {
  std::string input, output;
  bool force = false;
  if (int code = readFileArguments(args, "preview", kUsage, input, output, force)) return code;
  if (input.empty() || output.empty()) return usageError(std::string("preview: ") + kUsage);
  const std::string extension = fs::path(output).extension().string();
  if (extension != ".png" && extension != ".svg")
    return usageError("preview: '" + output + "': the picture is a .png or an .svg");
  std::error_code ec;
  if (!force && fs::exists(output, ec)) return usageError("preview: '" + output + "' exists; pass --force to replace it");
  nlohmann::json spec;
  if (int code = readSpecFile(input, spec)) return code;
  SamplePreview preview;
  try {
    const std::atomic<bool> never{false};
    preview = buildSamplePreview(parseSpec(spec), never);
  } catch (const SpecError& e) {
    return reportSpecError(input, e);
  } catch (const PreviewNotAvailable& e) {
    return usageError(std::string("preview: ") + e.what());
  }
  render::SamplePictureRequest request;
  request.format = extension == ".svg" ? render::ImageFormat::Svg : render::ImageFormat::Png;
  const render::SamplePicture picture = render::renderSamplePicture(preview, request);
  std::ofstream out(output, std::ios::binary);
  out << picture.bytes;
  if (!out) throw std::runtime_error("cannot write '" + output + "'");
  for (const std::string& fact : preview.facts) std::cout << fact << "\n";
  std::cout << output << "\n";
  return 0;
}

}  // namespace rupture::cli
