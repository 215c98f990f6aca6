// Replaces the global operator new / delete to count heap allocations (tests that a hot path allocates
// nothing). A separate translation unit, so GCC does not pair the inlined free with a new expression.
#include <cstdlib>
#include <new>

long g_allocations = 0;

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
