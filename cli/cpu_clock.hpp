#pragma once
// Process CPU time, accumulated over start()/stop() intervals. CPU rather than wall time, because
// the machines the comparisons run on are shared: another process slows the wall clock, not the
// CPU seconds this process spends.
#include <ctime>

namespace terrace::cli {

class CpuClock {
public:
    void start() {
        started_ = now();
        running_ = true;
    }
    /// Ends the interval begun by start(); without one running, nothing happens.
    void stop() {
        if (running_) total_ += now() - started_;
        running_ = false;
    }
    void reset() { total_ = 0.0; }
    double seconds() const { return total_; }

    static double now() {
        timespec ts{};
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
        return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
    }

private:
    double started_ = 0.0;
    double total_ = 0.0;
    bool running_ = false;
};

} // namespace terrace::cli
