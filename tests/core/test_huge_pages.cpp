// Large per-body arrays in huge pages (core/huge_pages.hpp): where their blocks lie and what the
// kernel is told of them, read back from /proc/self/smaps. Whether the kernel then backs them with
// huge pages depends on its mode and free memory, so that is measured (docs/PERFORMANCE.md), not
// tested; the advice, the alignment and the contents are.
#include "core/huge_pages.hpp"
#include <cstdint>
#include <cstdlib>
#include <gtest/gtest.h>
#include <optional>
#include <stdexcept>
#include <string>
#include <sys/mman.h>

namespace test_huge_pages {

using namespace terrace;

namespace {
// The kernel has transparent huge pages (in any mode) when it takes MADV_HUGEPAGE on a mapping of
// its own (EINVAL otherwise); the advice then shows as "hg" among the mapping's VmFlags.
bool kernelHasHugePages() {
    const std::size_t bytes = 2 * hugePageBytes;
    void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::runtime_error("test: no scratch mapping");
    const bool taken = madvise(p, bytes, MADV_HUGEPAGE) == 0;
    munmap(p, bytes);
    return taken;
}
std::uintptr_t address(const void* p) {
    return reinterpret_cast<std::uintptr_t>(p);
}

// Starts a test without TERRACE_HUGE_PAGES and restores it as the test found it.
class SwitchRestored {
public:
    SwitchRestored() {
        if (const char* v = std::getenv("TERRACE_HUGE_PAGES")) before_ = v;
        unsetenv("TERRACE_HUGE_PAGES");
    }
    ~SwitchRestored() {
        if (before_)
            setenv("TERRACE_HUGE_PAGES", before_->c_str(), 1);
        else
            unsetenv("TERRACE_HUGE_PAGES");
    }

private:
    std::optional<std::string> before_;
};
} // namespace

TEST(HugePages, ALargeArrayStartsOnAHugePageBoundaryAndIsAdvised) {
    SwitchRestored restored;
    BodyArray<double> values(hugePageBytes / sizeof(double) + 3);
    EXPECT_EQ(address(values.data()) % hugePageBytes, 0u);
    const PagesOfMapping pages = pagesOfMapping(values.data());
    ASSERT_TRUE(pages.found) << "no mapping in /proc/self/smaps holds the block";
    EXPECT_EQ(pages.advised, kernelHasHugePages());
    for (std::size_t k = 0; k < values.size(); ++k)
        values[k] = double(k);
    for (std::size_t k = 0; k < values.size(); k += 4099)
        ASSERT_EQ(values[k], double(k));
    EXPECT_EQ(values.back(), double(values.size() - 1));
}

TEST(HugePages, ASmallArrayComesFromTheHeapAlignedToACacheLine) {
    BodyArray<char> bytes(1000, 'x');
    EXPECT_EQ(address(bytes.data()) % 64, 0u);
    const PagesOfMapping pages = pagesOfMapping(bytes.data());
    ASSERT_TRUE(pages.found);
    // The heap is advised only where glibc's own huge-page tunable asks for it.
    const char* tunables = std::getenv("GLIBC_TUNABLES");
    if (!(tunables && std::string(tunables).find("hugetlb") != std::string::npos)) {
        EXPECT_FALSE(pages.advised);
    }
}

TEST(HugePages, TheSwitchMapsWithoutAdviceAndRefusesOtherValues) {
    SwitchRestored restored;
    setenv("TERRACE_HUGE_PAGES", "0", 1);
    EXPECT_FALSE(hugePagesWanted());
    {
        BodyArray<double> values(hugePageBytes / sizeof(double));
        EXPECT_EQ(address(values.data()) % hugePageBytes, 0u);
        const PagesOfMapping pages = pagesOfMapping(values.data());
        ASSERT_TRUE(pages.found);
        EXPECT_FALSE(pages.advised);
        EXPECT_EQ(pages.hugeBytes, 0u);
    }
    setenv("TERRACE_HUGE_PAGES", "1", 1);
    EXPECT_TRUE(hugePagesWanted());
    setenv("TERRACE_HUGE_PAGES", "yes", 1);
    EXPECT_THROW(hugePagesWanted(), std::invalid_argument);
    EXPECT_THROW({ BodyArray<double> refused(hugePageBytes / sizeof(double)); },
                 std::invalid_argument);
}

namespace {
// A rod's state is aligned to 32 B (core/linear_rotor.hpp); growth from the heap into a mapping
// and back must keep every element and its alignment, below a cache line's and above it.
template <class Aligned> void growAcrossTheThresholdAndBack() {
    BodyArray<Aligned> items;
    const std::size_t n = 2 * hugePageBytes / sizeof(Aligned);
    for (std::size_t k = 0; k < n; ++k) {
        items.push_back({double(k), -double(k), 0.5 * double(k)});
        ASSERT_EQ(address(items.data()) % alignof(Aligned), 0u);
    }
    EXPECT_EQ(address(items.data()) % hugePageBytes, 0u);
    for (std::size_t k = 0; k < n; k += 1021)
        ASSERT_EQ(items[k].x, double(k));
    items.resize(10);
    items.shrink_to_fit(); // back to the heap
    ASSERT_EQ(items.size(), 10u);
    EXPECT_EQ(address(items.data()) % alignof(Aligned), 0u);
    for (std::size_t k = 0; k < items.size(); ++k) {
        EXPECT_EQ(items[k].y, -double(k));
        EXPECT_EQ(items[k].z, 0.5 * double(k));
    }
}
struct alignas(32) Aligned32 {
    double x, y, z;
};
struct alignas(128) Aligned128 {
    double x, y, z;
};
} // namespace

TEST(HugePages, ContentsAndAlignmentSurviveGrowthAcrossTheThreshold) {
    growAcrossTheThresholdAndBack<Aligned32>();
    growAcrossTheThresholdAndBack<Aligned128>();
}

TEST(HugePages, AnAddressOutsideEveryMappingHasNone) {
    const PagesOfMapping none = pagesOfMapping(reinterpret_cast<const void*>(std::uintptr_t{8}));
    EXPECT_FALSE(none.found);
    EXPECT_FALSE(none.advised);
    EXPECT_EQ(none.hugeBytes, 0u);
}

} // namespace test_huge_pages
