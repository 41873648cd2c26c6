#pragma once
// A text file written whole or not at all: to a unique temporary beside the target, then renamed
// onto it, so readers (ParaView, the job server, a browser) never see a half-written file and
// concurrent writers never share a temporary. Used by the XDMF sidecars and the validation report.
#include <string>

namespace rupture::io {

/// Writes `text` to `path`; throws std::runtime_error (naming the file) when the write or the
/// rename fails, leaving no temporary behind.
void writeTextAtomically(const std::string& path, const std::string& text);

}  // namespace rupture::io
