#pragma once
// printf-style formatting into a std::string of whatever length the text needs. Messages and
// verdicts print numbers with a chosen precision (%.3g, %.2f), which std::format in g++ 12 does
// not yet offer; the attribute lets the compiler check each format against its arguments.
#include <cstdarg>
#include <cstdio>
#include <string>

namespace terrace {

[[gnu::format(printf, 1, 2)]] inline std::string formatText(const char* format, ...) {
    va_list args;
    va_start(args, format);
    va_list measure;
    va_copy(measure, args);
    const int length = std::vsnprintf(nullptr, 0, format, measure);
    va_end(measure);
    std::string text(std::size_t(length > 0 ? length : 0) + 1, '\0');
    if (length > 0) std::vsnprintf(text.data(), text.size(), format, args);
    va_end(args);
    text.resize(text.size() - 1);
    return text;
}

} // namespace terrace
