#pragma once
// A vector for scratch that every use overwrites before reading (the pair loop's records and
// chunk sums, the neighbour lists' buffers): growing it allocates but writes nothing. A
// std::vector value-initialises what it grows by, which for millions of particles zero-fills
// hundreds of megabytes in one uninterruptible stretch (0.5 s on a 2.3 M-particle column's first
// evaluation, more on a loaded host, where a cancel must be honoured within a second). Left
// untouched, the pages are faulted in by the parallel passes that fill them, between their polls.
#include <memory>
#include <type_traits>
#include <vector>

namespace rupture {

/// std::allocator whose value construction default-initialises (leaves trivial types unwritten).
template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  static_assert(std::is_trivially_default_constructible_v<T>, "scratch elements must need no construction");
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() noexcept = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}

  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    std::allocator_traits<std::allocator<T>>::construct(static_cast<std::allocator<T>&>(*this), p,
                                                        std::forward<Args>(args)...);
  }
};

/// Scratch storage: resize leaves new elements unwritten (see above).
template <class T>
using ScratchVector = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace rupture
