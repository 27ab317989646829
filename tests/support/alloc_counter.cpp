#include "support/alloc_counter.hpp"

#include <cstdlib>
#include <new>

namespace {
thread_local bool g_counting = false;
thread_local int g_allocations = 0;
}  // namespace

namespace foresight::test {
void set_allocation_counting(bool on) { g_counting = on; }
int allocations_counted() { return g_allocations; }
}  // namespace foresight::test

// Every form of the global operators is replaced, so each allocation and its release go through
// malloc / free (a form left to the runtime, such as the nothrow new std::stable_sort uses,
// would pair the runtime's new with this free: AddressSanitizer reports the mismatch).
// Kept in their own translation unit: inlined next to library code, GCC's
// -Wmismatched-new-delete takes the malloc / free pair for a mismatch.
void* operator new(std::size_t n) {
  if (g_counting) ++g_allocations;
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  if (g_counting) ++g_allocations;
  return std::malloc(n == 0 ? 1 : n);
}
void* operator new[](std::size_t n, const std::nothrow_t& tag) noexcept { return operator new(n, tag); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
