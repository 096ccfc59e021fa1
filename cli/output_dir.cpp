#include "cli/output_dir.hpp"
#include "core/output_file.hpp"
#include <cerrno>
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

namespace terrace::cli {

namespace fs = std::filesystem;

const std::vector<std::string>& runFileNames() {
    // samples.bin: the samples of restart formats before 6, still cleared by --overwrite.
    static const std::vector<std::string> names = {
        "summary.json", "scene.json", "initial.xyz", "trajectory.xyz", "thermo.csv", "rdf.csv",
        "vacf.csv",     "oacf.csv",   "msd.csv",     "restart.bin",    "samples.bin"};
    return names;
}

std::string sanitisedName(const std::string& name) {
    std::string out;
    for (const char c : name) {
        const bool safe = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                          (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.';
        out += safe ? c : '_';
    }
    const auto first = out.find_first_not_of('.');
    out = first == std::string::npos ? "" : out.substr(first);
    return out.empty() ? "scene" : out;
}

namespace {

/// The run files in dir, and the temporaries of whole-file writes a killed run left behind
/// (core/output_file.hpp names them ".<file>.partial-<pid>").
std::vector<std::string> presentRunFiles(const fs::path& dir) {
    std::vector<std::string> present;
    for (const auto& name : runFileNames()) {
        std::error_code ec;
        if (fs::symlink_status(dir / name, ec).type() != fs::file_type::not_found && !ec)
            present.push_back(name);
    }
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        const std::string name = entry.path().filename().string();
        for (const auto& file : runFileNames())
            if (name.rfind("." + file + ".partial-", 0) == 0) present.push_back(name);
    }
    return present;
}

std::string listed(const std::vector<std::string>& names) {
    std::string text;
    for (const auto& n : names)
        text += (text.empty() ? "" : ", ") + n;
    return text;
}

} // namespace

OutputDirectory::OutputDirectory(const fs::path& dir, OutputMode mode) : dir_(dir) {
    std::error_code ec;
    if (mode == OutputMode::Continue) {
        if (!fs::is_directory(dir, ec))
            throwIoError("use", dir, fs::exists(dir, ec) ? ENOTDIR : ENOENT);
    } else {
        fs::create_directories(dir, ec);
        if (ec) throwIoError("create the output directory", dir, ec.value());
        if (!fs::is_directory(dir, ec)) throwIoError("use as the output directory", dir, ENOTDIR);
    }
    const fs::path lockPath = dir / ".terrace.lock";
    lock_ = ::open(lockPath.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (lock_ < 0) throwIoError("write into", dir, errno);
    if (::flock(lock_, LOCK_EX | LOCK_NB) != 0) {
        const int err = errno;
        ::close(lock_);
        lock_ = -1;
        if (err == EWOULDBLOCK)
            throw IoError(dir.string() +
                          ": another terrace run is writing into this directory (it holds " +
                          lockPath.string() + "); wait for it or choose another --out");
        throwIoError("lock", lockPath, err);
    }
    if (mode == OutputMode::Continue) return;
    const auto present = presentRunFiles(dir);
    if (present.empty()) return;
    if (mode == OutputMode::Fresh) {
        ::close(lock_);
        lock_ = -1;
        throw IoError(dir.string() + " holds an earlier run's results (" + listed(present) +
                      "): choose another --out, add --overwrite to replace them, or "
                      "--continue " +
                      dir.string() + " to resume it");
    }
    for (const auto& name : present)
        if (fs::remove(dir / name, ec); ec) {
            ::close(lock_);
            lock_ = -1;
            throwIoError("remove", dir / name, ec.value());
        }
}

OutputDirectory::~OutputDirectory() {
    if (lock_ >= 0) ::close(lock_); // closing releases the flock
}

} // namespace terrace::cli
