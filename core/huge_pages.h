#pragma once
// Large fresh buffers and the page faults they cost. A tessellation of millions of vertices
// writes hundreds of megabytes into memory that the kernel hands out (and zeroes) one 4 KiB page
// at a time; on the 2-core test machine that was more than half of the run. Asking for
// transparent huge pages (Linux, "madvise" mode) before the first write makes it 2 MiB at a time.
// A hint only: where the kernel or platform does not take it, nothing changes.

#include <cstddef>
#include <vector>

namespace patchwork {

/// Advises the kernel to back the whole 2 MiB pages inside [data, data + bytes) with huge pages
/// (no-op below 4 MiB, off Linux, or if the kernel refuses).
void advise_huge_pages(const void* data, std::size_t bytes) noexcept;

/// v.reserve(n), then advise_huge_pages on the new storage before anything is written to it.
template <class T, class Allocator>
void reserve_huge(std::vector<T, Allocator>& v, std::size_t n) {
  v.reserve(n);
  advise_huge_pages(v.data(), v.capacity() * sizeof(T));
}

/// v with n elements, its storage kept when it has room, else made anew with reserve_huge (the
/// old contents are not kept then: for arrays about to be overwritten).
template <class T, class Allocator>
void resize_keeping_storage(std::vector<T, Allocator>& v, std::size_t n) {
  if (v.capacity() < n) {
    v = {};
    reserve_huge(v, n);
  }
  v.resize(n);
}

}  // namespace patchwork
