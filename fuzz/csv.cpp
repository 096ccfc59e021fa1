// Correlation CSVs as terrace compare reads them: both files, and the comparison.
#include "analysis/csv.hpp"
#include "analysis/compare.hpp"
#include "fuzz/support.hpp"
#include "fuzz/targets.hpp"

namespace terrace::fuzz {

void csvInput(std::string_view bytes) {
    static constexpr std::string_view separator = "\n%%\n";
    const auto at = bytes.find(separator);
    const auto a = scratchDirectory() / "a.csv", b = scratchDirectory() / "b.csv";
    writeFile(a, bytes.substr(0, at));
    writeFile(b, at == std::string_view::npos ? bytes : bytes.substr(at + separator.size()));
    try {
        (void)analysis::compareCsv(a, b, 3.0);
    } catch (const analysis::CsvError&) {
    }
}

} // namespace terrace::fuzz

#ifdef TERRACE_LIBFUZZER
extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, unsigned long size) {
    terrace::fuzz::csvInput({reinterpret_cast<const char*>(data), size});
    return 0;
}
#endif
