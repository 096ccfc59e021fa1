#include "analysis/cancellation.hpp"

namespace terrace::analysis {

namespace {
thread_local std::function<bool()> current;
} // namespace

ScopedCancellation::ScopedCancellation(std::function<bool()> cancelled)
    : previous_(std::move(current)) {
    current = std::move(cancelled);
}

ScopedCancellation::~ScopedCancellation() {
    current = std::move(previous_);
}

void throwIfCancelled() {
    if (current && current()) throw Cancelled();
}

} // namespace terrace::analysis
