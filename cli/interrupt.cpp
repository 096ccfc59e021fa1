#include "cli/interrupt.hpp"
#include <unistd.h>

namespace terrace::cli {

namespace {
std::atomic<bool> stopRequested{false};
void (*previousHandler)(int) = SIG_DFL;

extern "C" void onInterrupt(int) {
    if (stopRequested.exchange(true)) _exit(130);
    static const char msg[] =
        "\nterrace: interrupted; finishing the current sample and writing output"
        " (Ctrl-C again to abort)\n";
    [[maybe_unused]] auto n = write(2, msg, sizeof msg - 1);
}
} // namespace

InterruptGuard::InterruptGuard() {
    stopRequested = false;
    previousHandler = std::signal(SIGINT, onInterrupt);
}
InterruptGuard::~InterruptGuard() {
    std::signal(SIGINT, previousHandler);
}
bool InterruptGuard::requested() const {
    return stopRequested.load();
}

} // namespace terrace::cli
