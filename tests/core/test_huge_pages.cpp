// Large per-body arrays in huge pages (core/huge_pages.hpp): where their blocks lie and what the
// kernel is told of them, read back from /proc/self/smaps. Whether the kernel then backs them with
// huge pages depends on its mode and free memory, so that is measured (docs/PERFORMANCE.md), not
// tested; the advice, the alignment and the contents are.
#include "core/huge_pages.hpp"
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <gtest/gtest.h>
#include <stdexcept>
#include <string>

using namespace terrace;

namespace {
// The kernel has transparent huge pages (in any mode): MADV_HUGEPAGE is then taken and shows as
// "hg" among the mapping's VmFlags.
bool kernelHasHugePages() {
    return std::filesystem::exists("/sys/kernel/mm/transparent_hugepage/enabled");
}
std::uintptr_t address(const void* p) {
    return reinterpret_cast<std::uintptr_t>(p);
}

struct UnsetSwitch { // leaves TERRACE_HUGE_PAGES as the test found it: unset
    ~UnsetSwitch() { unsetenv("TERRACE_HUGE_PAGES"); }
};
} // namespace

TEST(HugePages, ALargeArrayStartsOnAHugePageBoundaryAndIsAdvised) {
    UnsetSwitch unset;
    unsetenv("TERRACE_HUGE_PAGES");
    BodyArray<double> values(hugePageThreshold / sizeof(double) + 3);
    EXPECT_EQ(address(values.data()) % hugePageBytes, 0u);
    const PagesOfMapping pages = pagesOfMapping(values.data());
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
    // The heap is advised only where glibc's own huge-page tunable asks for it.
    const char* tunables = std::getenv("GLIBC_TUNABLES");
    if (!(tunables && std::string(tunables).find("hugetlb") != std::string::npos))
        EXPECT_FALSE(pagesOfMapping(bytes.data()).advised);
}

TEST(HugePages, TheSwitchMapsWithoutAdviceAndRefusesOtherValues) {
    UnsetSwitch unset;
    setenv("TERRACE_HUGE_PAGES", "0", 1);
    EXPECT_FALSE(hugePagesWanted());
    {
        BodyArray<double> values(hugePageThreshold / sizeof(double));
        EXPECT_EQ(address(values.data()) % hugePageBytes, 0u);
        EXPECT_FALSE(pagesOfMapping(values.data()).advised);
    }
    setenv("TERRACE_HUGE_PAGES", "1", 1);
    EXPECT_TRUE(hugePagesWanted());
    setenv("TERRACE_HUGE_PAGES", "yes", 1);
    EXPECT_THROW(hugePagesWanted(), std::invalid_argument);
    EXPECT_THROW({ BodyArray<double> refused(hugePageThreshold / sizeof(double)); },
                 std::invalid_argument);
}

// A rod's state is aligned to 32 B (core/linear_rotor.hpp); growth from the heap into a mapping
// and back must keep every element and its alignment.
TEST(HugePages, ContentsAndAlignmentSurviveGrowthAcrossTheThreshold) {
    struct alignas(32) Aligned {
        double x, y, z;
    };
    BodyArray<Aligned> items;
    const std::size_t n = 2 * hugePageThreshold / sizeof(Aligned);
    for (std::size_t k = 0; k < n; ++k) {
        items.push_back({double(k), -double(k), 0.5 * double(k)});
        ASSERT_EQ(address(items.data()) % alignof(Aligned), 0u);
    }
    EXPECT_EQ(address(items.data()) % hugePageBytes, 0u);
    items.resize(10);
    items.shrink_to_fit(); // back to the heap
    ASSERT_EQ(items.size(), 10u);
    for (std::size_t k = 0; k < items.size(); ++k)
        EXPECT_EQ(items[k].y, -double(k));
    for (std::size_t k = 0; k < 10; ++k)
        EXPECT_EQ(items[k].z, 0.5 * double(k));
}

TEST(HugePages, AnAddressOutsideEveryMappingHasNone) {
    const PagesOfMapping none = pagesOfMapping(reinterpret_cast<const void*>(std::uintptr_t{8}));
    EXPECT_FALSE(none.advised);
    EXPECT_EQ(none.hugeBytes, 0u);
}
