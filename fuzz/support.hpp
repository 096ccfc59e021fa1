#pragma once
// What the fuzz entries share: the readers take file paths, so each input is written to a file
// in a directory of this process's own, and the "--set" lines that stand for the command line.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace terrace::fuzz {

/// A fresh directory of this process's own under the system's temporary directory, made once.
const std::filesystem::path& scratchDirectory();

/// Writes bytes to path, replacing what was there.
void writeFile(const std::filesystem::path& path, std::string_view bytes);

/// Takes the leading lines "--set key=value" off `bytes` (which then holds the rest) and returns
/// their "key=value" parts, as terrace run's --set options would hand them on.
std::vector<std::string> takeSetLines(std::string_view& bytes);

} // namespace terrace::fuzz
