#pragma once
// An allocator for the search's few large arrays (the join's half list and its occupancy
// table): from 512 KiB up, whole 2 MiB pages mapped for the array
// alone and offered to the kernel as huge pages. The first touch of a 4 KiB page is a page
// fault, some 12-16 us each on a virtual machine; one huge page replaces 512 of them. Where
// the kernel gives none (transparent huge pages off) the mapping behaves as any other.
// Smaller arrays come from the usual heap.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace gbx::rt {

template <class T> struct LargePages {
  using value_type = T;
  static constexpr std::size_t kPage = std::size_t{2} << 20;
  // From a quarter of a huge page up: one huge page's zeroing costs less than the faults of
  // 64 small ones.
  static constexpr std::size_t kLeast = kPage / 4;

  LargePages() = default;
  template <class U> LargePages(const LargePages<U>&) noexcept {}

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (n <= SIZE_MAX / sizeof(T) && bytes >= kLeast) {
      const std::size_t size = rounded(bytes);
      // Mapped one page over, then trimmed to a page boundary at both ends.
      void* raw = mmap(nullptr, size + kPage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
      if (raw == MAP_FAILED) throw std::bad_alloc();
      auto start = reinterpret_cast<std::uintptr_t>(raw);
      auto aligned = (start + kPage - 1) & ~(std::uintptr_t{kPage} - 1);
      if (aligned > start) munmap(raw, aligned - start);
      if (auto tail = start + size + kPage - (aligned + size); tail > 0)
        munmap(reinterpret_cast<void*>(aligned + size), tail);
      madvise(reinterpret_cast<void*>(aligned), size, MADV_HUGEPAGE);
      return reinterpret_cast<T*>(aligned);
    }
#endif
    return std::allocator<T>().allocate(n);
  }

  void deallocate(T* p, std::size_t n) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (n * sizeof(T) >= kLeast) {
      munmap(p, rounded(n * sizeof(T)));
      return;
    }
#endif
    std::allocator<T>().deallocate(p, n);
  }

  static std::size_t rounded(std::size_t bytes) { return (bytes + kPage - 1) & ~(kPage - 1); }
};

template <class T, class U> bool operator==(const LargePages<T>&, const LargePages<U>&) { return true; }
template <class T, class U> bool operator!=(const LargePages<T>&, const LargePages<U>&) { return false; }

template <class T> using LargeVector = std::vector<T, LargePages<T>>;

} // namespace gbx::rt
