#pragma once
// SHA-256 (FIPS 180-4): the digest a result's provenance gives its spec, so that two files made
// from the same spec can be told apart from two made from different ones by anyone with a standard
// tool (`sha256sum`). Small inputs only are hashed here (specs, not result files).
#include <string>
#include <string_view>

namespace rupture {

/// The SHA-256 digest of `bytes` as 64 lower-case hex digits.
std::string sha256Hex(std::string_view bytes);

}  // namespace rupture
