#pragma once
// Reading a JSON request body into a document, with every client mistake a 400 problem that says
// where: NUL bytes (nlohmann's lexer treats '\0' as the end of input and would ignore the rest),
// invalid UTF-8, nesting too deep for the recursive parser, syntax errors, and numbers outside the
// range of a double ("1e400"), named by the dotted path of their field.
#include <string>

#include "common/problem.hpp"

namespace rupture::server {

/// Deepest nesting of arrays and objects accepted in a body (the spec reader's limit).
inline constexpr int kMaxJsonDepth = 64;  // = io::kMaxJsonNesting

/// Parses the whole of `body` (its length, not its first NUL). Throws ApiError (400) naming the
/// byte offset or the field at fault.
Json parseJsonBody(const std::string& body);

/// The dotted path of the first object key that is the empty string under `value` ("" when none);
/// `path` is the path of `value` itself.
std::string findEmptyKey(const Json& value, const std::string& path);

}  // namespace rupture::server
