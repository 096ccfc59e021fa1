#pragma once
// Output that is whole or absent. Every file a run writes goes through one of two paths:
//   writeFileAtomically  the content goes to a temporary name beside the target, is flushed to
//                        the disk (fsync) and renamed over the target: a reader sees the old file
//                        or the new one, never half of one, whatever stops the process;
//   AppendFile           a growing file (trajectory frames, stored samples) written one record
//                        per write(2) call: a record that cannot be written whole (a full disk,
//                        a file-size limit) is cut off again, so the file ends on a record.
// Every failure is an IoError naming the file and the system's cause, e.g.
// "cannot write out/x/summary.json: No space left on device".
#include <cstdint>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace terrace {

class IoError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// "cannot <what> <path>: <strerror(err)>".
[[noreturn]] void throwIoError(const std::string& what, const std::filesystem::path& path, int err);

/// Replaces `path` with `content` atomically (temporary file, fsync, rename).
void writeFileAtomically(const std::filesystem::path& path, std::string_view content);
/// Hands each piece of a content to the file being written.
using PieceSink = std::function<void(std::string_view)>;
/// The same, for a content too large to hold whole: `produce` hands it over piece by piece, in
/// order, to the sink it is given. Should `produce` throw, the target is left as it was.
void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const PieceSink&)>& produce);

/// The whole content of a file; IoError naming the cause if it cannot be read.
std::string readWholeFile(const std::filesystem::path& path);

class AppendFile {
public:
    AppendFile() = default;
    /// Opens for appending; `truncateTo` < 0 keeps the content, otherwise cuts the file to that
    /// many bytes first (a continued run drops what came after its restart point). Creates the
    /// file if it does not exist.
    AppendFile(const std::filesystem::path& path, std::int64_t truncateTo);
    AppendFile(AppendFile&& other) noexcept;
    AppendFile& operator=(AppendFile&& other) noexcept;
    AppendFile(const AppendFile&) = delete;
    AppendFile& operator=(const AppendFile&) = delete;
    ~AppendFile();

    bool isOpen() const { return fd_ >= 0; }
    /// Appends the record whole, or throws IoError with the file cut back to where it was.
    void append(std::string_view record);
    /// The same for a record handed over in pieces by `produce` (a frame too large to hold
    /// whole): should a piece fail to be written, or `produce` throw, the file is cut back to
    /// where the record began.
    void appendPieces(const std::function<void(const PieceSink&)>& produce);
    /// Flushes what was appended to the disk (fdatasync): done before a restart file that counts
    /// these bytes is written, so that it never points past data the disk does not hold.
    void sync();
    /// Bytes in the file: where the next record starts.
    std::int64_t size() const { return size_; }
    const std::filesystem::path& path() const { return path_; }

private:
    void close() noexcept;

    std::filesystem::path path_;
    int fd_ = -1;
    std::int64_t size_ = 0;
};

} // namespace terrace
