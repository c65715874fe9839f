// Linked into every fuzzer: operator new and delete on malloc/free (still checked by ASan),
// with an impossible size throwing std::bad_alloc as it does in a normal build. ASan's own
// operator new aborts instead, so a size field damaged inside a library's file format (OpenVDB
// allocates a blosc chunk's stated size before reading it) would end every run although Talus's
// readers catch std::bad_alloc and refuse the file. 1 GB: below libFuzzer's malloc limit
// (-rss_limit_mb, 3 GB in tools/setup.sh) and far above any allocation a seed needs.
#include <cstdlib>
#include <new>

namespace {
void* allocate(std::size_t n) {
  if (n > (std::size_t(1) << 30)) throw std::bad_alloc();
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void* allocateOrNull(std::size_t n) noexcept {
  return n > (std::size_t(1) << 30) ? nullptr : std::malloc(n ? n : 1);
}
} // namespace

void* operator new(std::size_t n) { return allocate(n); }
void* operator new[](std::size_t n) { return allocate(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return allocateOrNull(n); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return allocateOrNull(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
