#pragma once
// Large per-body arrays in huge pages, where the kernel offers them.
//
// An event-driven step at N = 10⁶ reads some twenty lines at random over ~800 MB of per-body
// arrays, each on a page of its own; with 4-KiB pages nearly every one of them also misses the
// TLB (its second level maps 8 MiB), and the page walk comes before the line can even be asked
// for: a prefetch waits for it. With 2-MiB pages the same TLB maps 4 GiB. Linux gives an
// anonymous mapping huge pages on its own only when transparent huge pages are "always"; the
// common default (Debian's too) is "madvise", which gives them only to ranges advised with
// MADV_HUGEPAGE before they are touched. So blocks of a huge page and more are mapped
// here at a 2-MiB boundary and advised before anyone writes to them; smaller ones come from the
// ordinary heap. Nothing about the contents changes, only where the bytes lie.
//
// TERRACE_HUGE_PAGES=0 in the environment maps every block without the advice (1, or unset: with
// it), read at each large allocation, for measuring what the advice buys with one binary.
#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

namespace terrace {

inline constexpr std::size_t hugePageBytes = std::size_t{2} << 20;

/// Whether a block of `bytes` is mapped on a huge-page boundary and advised: from one huge page up
/// (a smaller block cannot hold one). Nothing is rounded up: the stretch past a block's last
/// boundary stays in small pages, so a block costs no more memory for its advice.
constexpr bool mappedInHugePages(std::size_t bytes) {
    return bytes >= hugePageBytes;
}

/// Whether large blocks are to be advised: TERRACE_HUGE_PAGES unset or "1" yes, "0" no; any other
/// value is an error (std::invalid_argument), so a misspelt switch is not silently ignored.
bool hugePagesWanted();

/// A page-aligned anonymous mapping of `bytes` (> 0) starting on a 2-MiB boundary, advised for
/// huge pages when `advise`; std::bad_alloc if the kernel refuses it.
void* mapLargeBlock(std::size_t bytes, bool advise);
void unmapLargeBlock(void* p, std::size_t bytes) noexcept;

/// What /proc/self/smaps says of the mapping that holds p: whether there is one (found: false also
/// where the file cannot be read), advised for huge pages (VmFlags "hg"), and how many of its
/// bytes lie in huge pages now (AnonHugePages).
struct PagesOfMapping {
    bool found = false;
    bool advised = false;
    std::size_t hugeBytes = 0;
};
PagesOfMapping pagesOfMapping(const void* p);

/// Bytes of this process in anonymous huge pages now (AnonHugePages of /proc/self/smaps_rollup;
/// 0 where it cannot be read).
std::size_t processHugePageBytes();

/// A standard allocator that maps the blocks mappedInHugePages names with mapLargeBlock and
/// takes smaller ones from the heap, every block aligned to at least a cache line. Stateless: any
/// two compare equal, so containers move and swap their blocks freely.
template <class T> struct HugePageAllocator {
    using value_type = T;
    HugePageAllocator() noexcept = default;
    template <class U> HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

    static constexpr std::size_t alignment = alignof(T) > 64 ? alignof(T) : 64;

    T* allocate(std::size_t n) {
        static_assert(alignof(T) <= hugePageBytes, "a mapped block is aligned to a huge page");
        if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
        const std::size_t bytes = n * sizeof(T);
        if (mappedInHugePages(bytes))
            return static_cast<T*>(mapLargeBlock(bytes, hugePagesWanted()));
        return static_cast<T*>(::operator new (bytes, std::align_val_t{alignment}));
    }
    void deallocate(T* p, std::size_t n) noexcept {
        const std::size_t bytes = n * sizeof(T);
        if (mappedInHugePages(bytes))
            unmapLargeBlock(p, bytes);
        else
            ::operator delete (p, bytes, std::align_val_t{alignment});
    }
    template <class U> bool operator==(const HugePageAllocator<U>&) const noexcept { return true; }
};

/// A per-body array that may be large: in huge pages from one huge page up.
template <class T> using BodyArray = std::vector<T, HugePageAllocator<T>>;

} // namespace terrace
