#include "cli/run_process.hpp"
#include "core/output_file.hpp"
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <string>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

extern char** environ;

namespace terrace::cli {

std::filesystem::path selfExecutable() {
    std::error_code ec;
    const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) throwIoError("find this executable at", "/proc/self/exe", ec.value());
    return self;
}

namespace {
std::filesystem::path chosenExecutable; // empty: this one
} // namespace

std::filesystem::path runExecutable() {
    return chosenExecutable.empty() ? selfExecutable() : chosenExecutable;
}

void setRunExecutable(const std::filesystem::path& executable) {
    chosenExecutable = executable;
}

bool stopWithSweep() {
    const char* value = std::getenv(sweepPidVariable);
    if (value == nullptr) return false;
    const pid_t sweep = pid_t(std::strtol(value, nullptr, 10));
    ::unsetenv(sweepPidVariable);
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != sweep) ::raise(SIGTERM); // the sweep ended before the line above
    return true;
}

namespace {
extern "C" void onChild(int) {} // only wakes ppoll; the loop reaps with waitpid
} // namespace

ChildWatch::ChildWatch() {
    struct sigaction action {};
    action.sa_handler = onChild;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_NOCLDSTOP;
    sigaction(SIGCHLD, &action, &previousAction_);
    sigset_t block;
    sigemptyset(&block);
    sigaddset(&block, SIGCHLD);
    sigprocmask(SIG_BLOCK, &block, &previousMask_);
}

ChildWatch::~ChildWatch() {
    sigprocmask(SIG_SETMASK, &previousMask_, nullptr);
    sigaction(SIGCHLD, &previousAction_, nullptr);
}

void ChildWatch::wait(std::chrono::milliseconds timeout) const {
    sigset_t open = previousMask_;
    sigdelset(&open, SIGCHLD);
    const long ms = long(timeout.count());
    const timespec ts{ms / 1000, (ms % 1000) * 1000000L};
    ::ppoll(nullptr, 0, &ts, &open); // EINTR on SIGCHLD or a stop signal: the caller looks
}

RunProcess::RunProcess(const SweepPlan& plan, const SweepRun& run, const std::filesystem::path& dir,
                       RunAction action) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throwIoError("create the run directory", dir, ec.value());

    std::vector<std::string> args = {runExecutable().string(), "run"};
    if (action == RunAction::Continue) {
        args.insert(args.end(), {"--continue", dir.string()});
    } else {
        if (!plan.scenePath.empty()) args.push_back(plan.scenePath.string());
        args.insert(args.end(), {"--out", dir.string(), "--overwrite"});
        for (const auto& o : plan.common)
            args.insert(args.end(), {"--set", overrideArgument(o)});
        for (const auto& o : run.overrides)
            args.insert(args.end(), {"--set", overrideArgument(o)});
    }
    args.push_back("--quiet");
    std::vector<char*> argv;
    for (auto& a : args)
        argv.push_back(a.data());
    argv.push_back(nullptr);
    // Appended, not built with operator+: GCC 12 at -O2 warns falsely (-Warray-bounds) of the
    // temporary that `std::string(...) + "="` makes.
    const std::string prefix = std::string(sweepPidVariable).append("=");
    std::vector<std::string> environment = {prefix + std::to_string(::getpid())};
    for (char** e = environ; *e != nullptr; ++e)
        if (std::string_view(*e).rfind(prefix, 0) != 0) environment.emplace_back(*e);
    std::vector<char*> envp;
    for (auto& e : environment)
        envp.push_back(e.data());
    envp.push_back(nullptr);

    posix_spawn_file_actions_t files;
    posix_spawnattr_t attr;
    posix_spawn_file_actions_init(&files);
    posix_spawnattr_init(&attr);
    const std::string log = (dir / "run.log").string();
    // A continued run's log goes on after the part that came before its restart.
    const int logFlags = O_WRONLY | O_CREAT | (action == RunAction::Continue ? O_APPEND : O_TRUNC);
    posix_spawn_file_actions_addopen(&files, 1, log.c_str(), logFlags, 0644);
    posix_spawn_file_actions_adddup2(&files, 1, 2);
    posix_spawn_file_actions_addopen(&files, 0, "/dev/null", O_RDONLY, 0);
    sigset_t defaults, none;
    sigemptyset(&defaults);
    for (const int s : {SIGINT, SIGTERM, SIGHUP, SIGXFSZ, SIGPIPE})
        sigaddset(&defaults, s);
    sigemptyset(&none);
    posix_spawnattr_setsigdefault(&attr, &defaults);
    posix_spawnattr_setsigmask(&attr, &none);
    posix_spawnattr_setpgroup(&attr, 0);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGDEF |
                                        POSIX_SPAWN_SETSIGMASK);
    const int err = posix_spawn(&pid_, argv[0], &files, &attr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&files);
    posix_spawnattr_destroy(&attr);
    if (err != 0) {
        pid_ = -1;
        throwIoError("start a run of", argv[0], err);
    }
}

RunProcess& RunProcess::operator=(RunProcess&& other) noexcept {
    if (this != &other) {
        this->~RunProcess();
        pid_ = other.pid_;
        other.pid_ = -1;
    }
    return *this;
}

RunProcess::~RunProcess() {
    if (pid_ > 0) {
        ::kill(pid_, SIGKILL);
        int status = 0;
        while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
        }
        pid_ = -1;
    }
}

std::optional<ChildExit> RunProcess::poll() {
    if (pid_ <= 0) return std::nullopt;
    int status = 0;
    const pid_t r = ::waitpid(pid_, &status, WNOHANG);
    if (r == 0 || (r < 0 && errno == EINTR)) return std::nullopt;
    pid_ = -1;
    if (r < 0) return ChildExit{false, 127}; // lost (ECHILD): counted as a failed run
    if (WIFSIGNALED(status)) return ChildExit{true, WTERMSIG(status)};
    return ChildExit{false, WEXITSTATUS(status)};
}

void RunProcess::signal(int sig) const {
    if (pid_ > 0) ::kill(pid_, sig);
}

} // namespace terrace::cli
