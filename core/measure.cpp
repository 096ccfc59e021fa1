#include "core/measure.hpp"
#include <algorithm>
#include <cstdlib>
#include <stdexcept>

namespace terrace {

MeasureSwitches parseMeasureSwitches(const std::string& text) {
    MeasureSwitches m;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t comma = std::min(text.find(',', start), text.size());
        const std::string word = text.substr(start, comma - start);
        if (word == "no-hold-screen")
            m.holdScreen = false;
        else if (word == "no-sort-dmd")
            m.sortDmd = false;
        else if (word == "no-sort-smd")
            m.sortSmd = false;
        else if (!(word.empty() && text.empty()))
            throw std::invalid_argument("TERRACE_MEASURE: unknown switch \"" + word +
                                        "\" (known: no-hold-screen, no-sort-dmd, no-sort-smd, "
                                        "separated by commas)");
        start = comma + 1;
    }
    return m;
}

MeasureSwitches measureSwitches() {
    const char* text = std::getenv("TERRACE_MEASURE");
    return parseMeasureSwitches(text ? text : "");
}

} // namespace terrace
