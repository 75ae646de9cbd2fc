// The kernel calls behind PagedArray: anonymous private mappings, whose pages are zero and take no
// memory until first written, grown with mremap so that untouched pages stay untouched.

#include "throng/actors/PagedArray.h"

#include <sys/mman.h>
#include <unistd.h>

#include <new>

namespace throng::detail {

void* mapPages(std::size_t bytes) {
    void* pages = ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (pages == MAP_FAILED) throw std::bad_alloc();
    return pages;
}

void* remapPages(void* pages, std::size_t oldBytes, std::size_t newBytes) {
    void* moved = ::mremap(pages, oldBytes, newBytes, MREMAP_MAYMOVE);
    if (moved == MAP_FAILED) throw std::bad_alloc();
    return moved;
}

void unmapPages(void* pages, std::size_t bytes) { ::munmap(pages, bytes); }

std::size_t pageBytes() {
    static const std::size_t bytes = [] {
        const long page = ::sysconf(_SC_PAGESIZE);
        return page > 0 ? std::size_t(page) : std::size_t(4096);
    }();
    return bytes;
}

}  // namespace throng::detail
