#include "core/huge_pages.hpp"

#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <sys/mman.h>
#include <unistd.h>

namespace terrace {

bool hugePagesWanted() {
    const char* v = std::getenv("TERRACE_HUGE_PAGES");
    if (!v || std::strcmp(v, "1") == 0) return true;
    if (std::strcmp(v, "0") == 0) return false;
    throw std::invalid_argument(std::string("TERRACE_HUGE_PAGES: must be 0 or 1, got \"") + v +
                                "\"");
}

namespace {
std::size_t pageRounded(std::size_t bytes) {
    static const std::size_t page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
    return (bytes + page - 1) / page * page;
}
} // namespace

void* mapLargeBlock(std::size_t bytes, bool advise) {
    if (bytes > std::numeric_limits<std::size_t>::max() / 2) throw std::bad_alloc();
    const std::size_t length = pageRounded(bytes);
    // Map a huge page more than asked for, then give back what lies before the first 2-MiB
    // boundary and after the block: a huge page can only back a 2-MiB-aligned stretch that lies
    // wholly inside an advised mapping. The tail past the last boundary stays in small pages,
    // so nothing beyond the block's own pages is ever resident.
    const std::size_t mapped = length + hugePageBytes;
    void* raw = mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (raw == MAP_FAILED) throw std::bad_alloc();
    const auto start = reinterpret_cast<std::uintptr_t>(raw);
    const std::uintptr_t aligned = (start + hugePageBytes - 1) & ~(hugePageBytes - 1);
    if (aligned > start) munmap(raw, aligned - start);
    const std::uintptr_t end = aligned + length;
    if (start + mapped > end) munmap(reinterpret_cast<void*>(end), start + mapped - end);
    // Advice the kernel cannot take (no transparent huge pages in it) leaves small pages: no error.
    if (advise) madvise(reinterpret_cast<void*>(aligned), length, MADV_HUGEPAGE);
    return reinterpret_cast<void*>(aligned);
}

void unmapLargeBlock(void* p, std::size_t bytes) noexcept {
    if (p) munmap(p, pageRounded(bytes));
}

PagesOfMapping pagesOfMapping(const void* p) {
    PagesOfMapping mapping;
    std::ifstream smaps("/proc/self/smaps");
    const auto address = reinterpret_cast<std::uintptr_t>(p);
    std::string line;
    bool inside = false;
    while (std::getline(smaps, line)) {
        unsigned long long from = 0, to = 0;
        // A mapping's header: "from-to perms offset dev inode path", addresses in hex.
        if (std::sscanf(line.c_str(), "%llx-%llx ", &from, &to) == 2 &&
            line.find('-') < line.find(' ')) {
            if (inside) break;
            inside = address >= from && address < to;
            mapping.found = mapping.found || inside;
            continue;
        }
        if (!inside) continue;
        std::istringstream fields(line);
        std::string key;
        fields >> key;
        if (key == "AnonHugePages:") {
            std::size_t kB = 0;
            fields >> kB;
            mapping.hugeBytes = kB * 1024;
        } else if (key == "VmFlags:") {
            std::string flag;
            while (fields >> flag)
                if (flag == "hg") mapping.advised = true;
        }
    }
    return mapping;
}

std::size_t processHugePageBytes() {
    std::ifstream rollup("/proc/self/smaps_rollup");
    std::string key;
    while (rollup >> key) {
        if (key == "AnonHugePages:") {
            std::size_t kB = 0;
            rollup >> kB;
            return kB * 1024;
        }
        rollup.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
    }
    return 0;
}

} // namespace terrace
