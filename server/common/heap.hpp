#pragma once
// Gives the heap's free pages back to the system. glibc keeps what a request freed in its arenas
// (a POST of a large sweep parses megabytes of JSON on a handler thread's arena) and the server's
// resident memory would stay at its high-water mark; malloc_trim returns the free pages of every
// arena. It walks the heap, so it runs after requests that allocated much, not after every one.
#include <cstddef>

namespace rupture::server {

/// Returns the free heap pages of every arena to the system (malloc_trim(0)); a no-op elsewhere.
void returnFreeHeapToSystem();

/// The process's resident memory (B) from /proc/self/statm; 0 where it cannot be read.
std::size_t residentBytes();

}  // namespace rupture::server
