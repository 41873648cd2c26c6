#pragma once
// Messages that leave the server (failed runs, job messages): engine and library errors name
// absolute paths and print pointers; a client needs neither, and they tell an attacker about the
// host. The message keeps its meaning: a path becomes its file name, an address becomes "0x...".
#include <string>

namespace rupture::server {

/// `message` as valid UTF-8 with absolute paths reduced to their last component and hexadecimal
/// addresses (0x followed by 6 or more hex digits) masked.
std::string publicMessage(const std::string& message);

}  // namespace rupture::server
