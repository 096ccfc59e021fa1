#include "cli/interrupt.hpp"
#include <cerrno>
#include <unistd.h>

namespace terrace::cli {

namespace {

constexpr int handled[] = {SIGINT, SIGTERM, SIGHUP};
std::atomic<int> received{0};
std::atomic<int> firstSignal{0};
struct sigaction previous[3];
struct sigaction previousXfsz;

void say(const char* text, std::size_t length) {
    [[maybe_unused]] auto n = write(2, text, length);
}

extern "C" void onSignal(int sig) {
    const int savedErrno = errno; // the code the signal interrupted may be about to read it
    int expected = 0;
    firstSignal.compare_exchange_strong(expected, sig);
    const int n = ++received;
    if (n >= 3) _exit(128 + firstSignal.load());
    static const char first[] =
        "\nterrace: signal received: stopping at the next sample and writing the output "
        "(a third time: exit at once)\n";
    static const char second[] =
        "\nterrace: second signal: the output is being written (a third signal exits at once)\n";
    if (n == 1)
        say(first, sizeof first - 1);
    else
        say(second, sizeof second - 1);
    errno = savedErrno;
}

} // namespace

InterruptGuard::InterruptGuard() {
    received = 0;
    firstSignal = 0;
    struct sigaction action {};
    action.sa_handler = onSignal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART; // reads and writes in progress go on; the loop checks the flag
    for (int k = 0; k < 3; ++k)
        sigaction(handled[k], &action, &previous[k]);
    struct sigaction ignore {};
    ignore.sa_handler = SIG_IGN;
    sigemptyset(&ignore.sa_mask);
    sigaction(SIGXFSZ, &ignore, &previousXfsz);
}

InterruptGuard::~InterruptGuard() {
    for (int k = 0; k < 3; ++k)
        sigaction(handled[k], &previous[k], nullptr);
    sigaction(SIGXFSZ, &previousXfsz, nullptr);
}

int InterruptGuard::count() const {
    return received.load();
}

int InterruptGuard::signal() const {
    return firstSignal.load();
}

std::string InterruptGuard::signalName() const {
    switch (signal()) {
    case SIGINT:
        return "SIGINT";
    case SIGTERM:
        return "SIGTERM";
    case SIGHUP:
        return "SIGHUP";
    case 0:
        return "";
    }
    return "signal " + std::to_string(signal());
}

} // namespace terrace::cli
