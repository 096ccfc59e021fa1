#pragma once
// TERRACE_MEASURE (core/measure.hpp) set for one scope and restored as it was found, so that a
// test can build an engine with a measurement switch on without leaking it into other tests.
#include <cstdlib>
#include <optional>
#include <string>

namespace terrace::testing {

class MeasureGuard {
public:
    explicit MeasureGuard(const std::string& switches) {
        if (const char* v = std::getenv(name)) before_ = v;
        setenv(name, switches.c_str(), 1);
    }
    ~MeasureGuard() {
        if (before_)
            setenv(name, before_->c_str(), 1);
        else
            unsetenv(name);
    }
    MeasureGuard(const MeasureGuard&) = delete;
    MeasureGuard& operator=(const MeasureGuard&) = delete;

private:
    static constexpr const char* name = "TERRACE_MEASURE";
    std::optional<std::string> before_;
};

} // namespace terrace::testing
