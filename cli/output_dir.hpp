#pragma once
// The output directory of a run, claimed before anything is written into it:
//   fresh      created if needed; refused when it holds any file a run writes (an earlier run's
//              results are never overwritten silently, nor mixed with the new ones);
//   overwrite  the same, but an earlier run's files are removed first, so nothing stale survives;
//   continue   must hold a restart file (cli/restart.hpp); the run extends what is there.
// A lock (flock on DIR/.terrace.lock, held until the object dies, released by the kernel however
// the process ends) keeps a second run from writing into the same directory at once.
#include <filesystem>
#include <string>
#include <vector>

namespace terrace::cli {

enum class OutputMode { Fresh, Overwrite, Continue };

/// Every file name a run may write into its directory.
const std::vector<std::string>& runFileNames();

/// A scene name made safe as one directory name under out/: letters, digits, '-', '_' and '.'
/// kept, anything else (a '/', a space) becomes '_', leading dots are dropped ("..", ".hidden"),
/// and an empty result is "scene".
std::string sanitisedName(const std::string& name);

class OutputDirectory {
public:
    OutputDirectory(const std::filesystem::path& dir, OutputMode mode);
    ~OutputDirectory();
    OutputDirectory(const OutputDirectory&) = delete;
    OutputDirectory& operator=(const OutputDirectory&) = delete;
    const std::filesystem::path& path() const { return dir_; }

private:
    std::filesystem::path dir_;
    int lock_ = -1;
};

} // namespace terrace::cli
