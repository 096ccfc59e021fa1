#include "cli/sweep_runner.hpp"
#include "cli/interrupt.hpp"
#include "cli/sweep_table.hpp"
#include "core/output_file.hpp"
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <deque>
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>
#include <vector>

namespace terrace::cli {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string duration(double seconds) {
    char text[32];
    const long s = long(seconds + 0.5);
    if (s >= 3600)
        std::snprintf(text, sizeof text, "%ldh%02ldm", s / 3600, s / 60 % 60);
    else if (s >= 60)
        std::snprintf(text, sizeof text, "%ldm%02lds", s / 60, s % 60);
    else
        std::snprintf(text, sizeof text, "%lds", s);
    return text;
}

/// flock on OUT/.sweep.lock for the sweep's life: two sweeps never hand out the same runs.
class SweepLock {
public:
    explicit SweepLock(const fs::path& out) {
        std::error_code ec;
        fs::create_directories(out, ec);
        if (ec) throwIoError("create the sweep directory", out, ec.value());
        const fs::path path = out / ".sweep.lock";
        fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (fd_ < 0) throwIoError("write into", out, errno);
        if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
            ::close(fd_);
            throw IoError(out.string() + ": another terrace sweep is running in this directory");
        }
    }
    ~SweepLock() { ::close(fd_); }
    SweepLock(const SweepLock&) = delete;
    SweepLock& operator=(const SweepLock&) = delete;

private:
    int fd_ = -1;
};

class Sweep {
public:
    Sweep(const SweepPlan& plan, const SweepOptions& options, RemoteWorkers* remote)
        : plan_(plan), options_(options), remote_(remote), entries_(plan.runs.size()),
          actions_(plan.runs.size(), RunAction::Fresh) {}

    int run() {
        const SweepLock lock(options_.out);
        for (std::size_t i = 0; i < plan_.runs.size(); ++i) {
            actions_[i] = resumeAction(dir(i), plan_.runs[i], options_.retryFailed, entries_[i]);
            if (actions_[i] == RunAction::Skip)
                ++reused_;
            else
                queue_.push_back(int(i));
        }
        writeTable();
        if (!options_.quiet)
            std::fprintf(
                stderr, "sweep: %zu runs, %d done before, %zu to run (%d local slot%s%s)\n",
                plan_.runs.size(), reused_, queue_.size(), options_.jobs,
                options_.jobs == 1 ? "" : "s",
                remote_ ? (", " + std::to_string(remote_->count()) + " remote workers").c_str()
                        : "");
        const InterruptGuard guard;
        const ChildWatch watch;
        const auto start = Clock::now();
        int stoppedWorkers = 0;
        bool forwarded = false;
        while (true) {
            bool progressed = false;
            if (!guard.requested()) progressed |= takeBackFreed();
            while (!guard.requested() && int(local_.size()) < options_.jobs) {
                const int i = nextFree();
                if (i < 0) break;
                local_.push_back(
                    {RunProcess(plan_, plan_.runs[i], dir(i), actions_[i]), i, Clock::now()});
                progressed = true;
            }
            for (auto slot = local_.begin(); slot != local_.end();) {
                if (const auto exit = slot->process.poll()) {
                    const int run = slot->run;
                    const double wall = secondsSince(slot->started);
                    slot = local_.erase(slot);
                    finish(run, *exit, wall, start);
                    progressed = true;
                } else {
                    ++slot;
                }
            }
            while (remote_ != nullptr) {
                const auto report = remote_->poll();
                if (!report) break;
                progressed = true;
                if (report->run >= 0) {
                    --remoteBusy_;
                    finish(report->run, report->exit, report->wallSeconds, start);
                }
                if (report->leaving)
                    ++stoppedWorkers;
                else
                    idle_.push_back(report->worker);
            }
            // A remote worker waits for a run while runs wait for their directories' locks; it
            // is let go once nothing is left to hand out.
            while (!guard.requested() && !idle_.empty()) {
                const int i = nextFree();
                if (i < 0) break;
                remote_->assign(idle_.back(), i, actions_[i]);
                idle_.pop_back();
                ++remoteBusy_;
                progressed = true;
            }
            if ((queue_.empty() && waiting_.empty()) || guard.requested()) {
                for (const int worker : idle_)
                    remote_->assign(worker, -1, RunAction::Skip);
                stoppedWorkers += int(idle_.size());
                idle_.clear();
            }
            if (guard.requested() && !forwarded) {
                for (const auto& slot : local_)
                    slot.process.signal(guard.signal());
                forwarded = true;
            }
            const bool handedOut = (queue_.empty() && waiting_.empty()) || guard.requested();
            const bool workersDone = remote_ == nullptr || stoppedWorkers == remote_->count();
            if (handedOut && local_.empty() && workersDone) break;
            // Remote reports have no signal to wake on: look for them every 10 ms.
            if (!progressed) watch.wait(std::chrono::milliseconds(remote_ ? 10 : 1000));
        }
        return report(guard, secondsSince(start));
    }

private:
    struct Slot {
        RunProcess process;
        int run;
        Clock::time_point started;
    };

    fs::path dir(std::size_t i) const { return options_.out / plan_.runs[i].name; }

    /// The next queued run whose directory no other process holds, or -1. Those held are set
    /// waiting: started now, a run would fail on the lock and be recorded failed ever after. For
    /// local and remote workers alike (a remote worker's run directory is on a file system rank 0
    /// sees too).
    int nextFree() {
        while (!queue_.empty()) {
            const int i = queue_.front();
            queue_.pop_front();
            if (!held(i)) return i;
            wait(i);
        }
        return -1;
    }

    /// Whether another process holds run i's directory lock (cli/output_dir.hpp): a run of an
    /// earlier sweep still ending.
    bool held(int i) const {
        const fs::path lock = dir(i) / ".terrace.lock";
        const int fd = ::open(lock.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd < 0) return false;
        const bool busy = ::flock(fd, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK;
        ::close(fd); // releases the lock, if taken
        return busy;
    }

    void wait(int i) {
        waiting_.push_back(i);
        if (!options_.quiet)
            std::fprintf(stderr,
                         "sweep: %s: another terrace run holds its directory's lock; waiting for "
                         "it to end\n",
                         plan_.runs[i].name.c_str());
    }

    /// The waiting runs whose directories are free again, taken for what they left (finished,
    /// continuable or to run afresh) and queued first, or counted done.
    bool takeBackFreed() {
        bool any = false;
        for (auto it = waiting_.begin(); it != waiting_.end();) {
            const int i = *it;
            if (held(i)) {
                ++it;
                continue;
            }
            it = waiting_.erase(it);
            any = true;
            actions_[i] = resumeAction(dir(i), plan_.runs[i], options_.retryFailed, entries_[i]);
            if (actions_[i] == RunAction::Skip)
                ++reused_;
            else
                queue_.push_front(i);
        }
        if (any) writeTable();
        return any;
    }

    void finish(int i, const ChildExit& exit, double wall, Clock::time_point start) {
        entries_[i] = finishedEntry(dir(i), plan_.runs[i], exit);
        entries_[i].wallSeconds = wall;
        runWall_ += wall;
        ++finished_;
        if (entries_[i].status == RunStatus::Failed) ++failed_;
        writeTable();
        if (options_.quiet) return;
        const int running = int(local_.size()) + remoteBusy_;
        const int slots = options_.jobs + (remote_ ? remote_->count() : 0);
        const double eta = runWall_ / finished_ * double(queue_.size() + running) / slots;
        std::fprintf(
            stderr, "sweep: [%d/%zu] %s %s (%s)%s%s; %d failed, %d running, elapsed %s, ETA %s\n",
            reused_ + finished_, plan_.runs.size(), plan_.runs[i].name.c_str(),
            statusName(entries_[i].status), duration(wall).c_str(),
            entries_[i].message.empty() ? "" : ": ", entries_[i].message.substr(0, 120).c_str(),
            failed_, running, duration(secondsSince(start)).c_str(), duration(eta).c_str());
    }

    void writeTable() const {
        writeFileAtomically(options_.out / "sweep.csv", sweepTable(plan_, entries_));
    }

    int report(const InterruptGuard& guard, double wall) const {
        int ok = 0, failed = 0, interrupted = 0, pending = 0;
        for (const auto& e : entries_) {
            ok += e.status == RunStatus::Ok;
            failed += e.status == RunStatus::Failed;
            interrupted += e.status == RunStatus::Interrupted;
            pending += e.status == RunStatus::Pending;
        }
        if (!options_.quiet) {
            std::fprintf(stderr,
                         "sweep: %zu runs: %d ok, %d failed, %d interrupted, %d not run; "
                         "table in %s\n",
                         plan_.runs.size(), ok, failed, interrupted, pending,
                         (options_.out / "sweep.csv").c_str());
            if (finished_ > 0)
                std::fprintf(stderr,
                             "sweep: %.2f s of wall time for %d runs taking %.2f s in all\n", wall,
                             finished_, runWall_);
        }
        if (guard.requested()) {
            std::fprintf(stderr, "sweep: stopped by %s; the same command goes on from here\n",
                         guard.signalName().c_str());
            return guard.exitStatus();
        }
        return failed > 0 ? 1 : 0;
    }

    const SweepPlan& plan_;
    const SweepOptions& options_;
    RemoteWorkers* remote_;
    std::vector<SweepEntry> entries_;
    std::vector<RunAction> actions_;
    std::deque<int> queue_;
    std::vector<int> waiting_; // runs whose directory another process holds
    std::vector<Slot> local_;
    std::vector<int> idle_; // remote workers that asked for a run and have none yet
    int reused_ = 0, finished_ = 0, failed_ = 0, remoteBusy_ = 0;
    double runWall_ = 0.0;
};

} // namespace

int runSweep(const SweepPlan& plan, const SweepOptions& options, RemoteWorkers* remote) {
    if (options.jobs < 0 || (options.jobs == 0 && remote == nullptr))
        throw SceneError("sweep: -j must be at least 1");
    return Sweep(plan, options, remote).run();
}

} // namespace terrace::cli
