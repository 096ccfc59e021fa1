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

/// The overrides ("key.path=value", as --set takes them) as part of a default output directory's
/// name, so that runs of one scene with different --set land apart: "key=value" for each key,
/// by the key's last component (the whole dotted key where two overrides share it), sorted by
/// the whole key, joined by ',', each made safe as sanitisedName does; an object value counts as
/// its leaves, a key set twice by its last value. `name` and `engine` are left out (the name
/// already says them), as are overrides that do not parse. "" for none. Over `maxLength`
/// characters, the text is cut and ends in '-' and 16 hex digits of its CRC-64 instead, so that
/// two long sets of overrides still differ.
std::string overridesName(const std::vector<std::string>& overrides, std::size_t maxLength = 160);

/// `base` (a sanitised name) followed by "-" and overridesName(overrides) when there are any.
std::string nameWithOverrides(const std::string& base, const std::vector<std::string>& overrides);

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
