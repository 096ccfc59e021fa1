#include "cli/output_dir.hpp"
#include "cli/restart.hpp"
#include "core/output_file.hpp"
#include "core/scene.hpp"
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <fcntl.h>
#include <map>
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

namespace {

/// Every character outside the safe set (letters, digits, '-', '_', '.') becomes '_'.
std::string safeCharacters(const std::string& text) {
    std::string out;
    for (const char c : text) {
        const bool safe = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                          (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.';
        out += safe ? c : '_';
    }
    return out;
}

} // namespace

std::string sanitisedName(const std::string& name) {
    std::string out = safeCharacters(name);
    const auto first = out.find_first_not_of('.');
    out = first == std::string::npos ? "" : out.substr(first);
    return out.empty() ? "scene" : out;
}

namespace {

/// An override's leaves: an object value stands for the keys under it.
void addLeaves(const std::string& key, const nlohmann::json& value,
               std::map<std::string, nlohmann::json>& leaves) {
    if (!value.is_object() || value.empty()) {
        leaves[key] = value;
        return;
    }
    for (const auto& [k, v] : value.items())
        addLeaves(key + "." + k, v, leaves);
}

std::string lastComponent(const std::string& key) {
    return key.substr(key.rfind('.') + 1);
}

} // namespace

std::string overridesName(const std::vector<std::string>& overrides, std::size_t maxLength) {
    std::map<std::string, nlohmann::json> leaves; // sorted by the whole key, the last value kept
    for (const std::string& o : overrides)
        if (const auto parsed = parseOverride(o)) addLeaves(parsed->first, parsed->second, leaves);
    leaves.erase("name");
    leaves.erase("engine");
    std::map<std::string, int> shared;
    for (const auto& [key, value] : leaves)
        ++shared[lastComponent(key)];
    std::string text;
    for (const auto& [key, value] : leaves) {
        const std::string shown = shared[lastComponent(key)] > 1 ? key : lastComponent(key);
        const std::string v = value.is_string() ? value.get<std::string>() : value.dump();
        text += (text.empty() ? "" : ",") + safeCharacters(shown) + "=" + safeCharacters(v);
    }
    if (text.size() <= maxLength) return text;
    char tag[20];
    std::snprintf(tag, sizeof tag, "-%016llx", static_cast<unsigned long long>(crc64(text)));
    return text.substr(0, maxLength - 17) + tag;
}

std::string nameWithOverrides(const std::string& base, const std::vector<std::string>& overrides) {
    const std::string suffix = overridesName(overrides);
    return suffix.empty() ? base : base + "-" + suffix;
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
        // --continue needs the restart file, which a finished run removes: named only then.
        const bool resumable =
            std::find(present.begin(), present.end(), "restart.bin") != present.end();
        throw IoError(dir.string() + " holds an earlier run's results (" + listed(present) +
                      "): add --overwrite to replace them or give another --out" +
                      (resumable ? ", or resume that run with --continue " + dir.string() : ""));
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
