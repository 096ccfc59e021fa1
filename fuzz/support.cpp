#include "fuzz/support.hpp"
#include <fstream>
#include <stdexcept>
#include <unistd.h>

namespace terrace::fuzz {

namespace {
// Removed when the process ends normally; a fuzzer stopped by a finding leaves it for a look.
struct Scratch {
    std::filesystem::path dir;
    Scratch()
        : dir(std::filesystem::temp_directory_path() /
              ("terrace-fuzz-" + std::to_string(::getpid()))) {
        std::filesystem::create_directories(dir);
    }
    ~Scratch() {
        std::error_code ec;
        std::filesystem::remove_all(dir, ec);
    }
};
} // namespace

const std::filesystem::path& scratchDirectory() {
    static const Scratch scratch;
    return scratch.dir;
}

void writeFile(const std::filesystem::path& path, std::string_view bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw std::logic_error("fuzz: cannot write " + path.string());
}

std::vector<std::string> takeSetLines(std::string_view& bytes) {
    static constexpr std::string_view prefix = "--set ";
    std::vector<std::string> sets;
    while (bytes.substr(0, prefix.size()) == prefix) {
        const auto end = bytes.find('\n');
        const auto line =
            bytes.substr(prefix.size(), end == std::string_view::npos ? std::string_view::npos
                                                                      : end - prefix.size());
        sets.emplace_back(line);
        bytes = end == std::string_view::npos ? std::string_view() : bytes.substr(end + 1);
    }
    return sets;
}

} // namespace terrace::fuzz
