#include "AllocationCounter.h"

#include <sys/resource.h>

#include <atomic>
#include <cerrno>
#include <cstddef>

#if defined(__SANITIZE_ADDRESS__)

namespace throng::testkit {
bool allocationsCounted() { return false; }
std::uint64_t heapAllocations() { return 0; }
}  // namespace throng::testkit

#else

// glibc's own entry points: the replacements below count, then hand over to them. A program's
// definition of malloc takes precedence over the C library's for every shared library too, so
// libstdc++'s operator new and the containers inside Throng's libraries are counted.
extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* p, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);
}

namespace {
std::atomic<std::uint64_t> gAllocations{0};
void counted() { gAllocations.fetch_add(1, std::memory_order_relaxed); }
}  // namespace

extern "C" {
void* malloc(std::size_t size) {
    counted();
    return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) {
    counted();
    return __libc_calloc(count, size);
}
void* realloc(void* p, std::size_t size) {
    counted();
    return __libc_realloc(p, size);
}
void* memalign(std::size_t alignment, std::size_t size) {
    counted();
    return __libc_memalign(alignment, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) {
    counted();
    return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t size) {
    counted();
    if (alignment % sizeof(void*) != 0 || (alignment & (alignment - 1)) != 0) return EINVAL;
    void* p = __libc_memalign(alignment, size);
    if (!p) return ENOMEM;
    *out = p;
    return 0;
}
}

namespace throng::testkit {
bool allocationsCounted() { return true; }
std::uint64_t heapAllocations() { return gAllocations.load(std::memory_order_relaxed); }
}  // namespace throng::testkit

#endif

namespace throng::testkit {
long minorPageFaults() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_minflt;
}
}  // namespace throng::testkit
