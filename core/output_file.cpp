#include "core/output_file.hpp"
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace terrace {

void throwIoError(const std::string& what, const std::filesystem::path& path, int err) {
    throw IoError("cannot " + what + " " + path.string() + ": " + std::strerror(err));
}

namespace {

/// write(2) until every byte is out; false with errno set when the system refuses.
bool writeAll(int fd, std::string_view data) {
    while (!data.empty()) {
        const ssize_t n = ::write(fd, data.data(), data.size());
        if (n < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        if (n == 0) {
            errno = ENOSPC; // a write that makes no progress: the device takes nothing more
            return false;
        }
        data.remove_prefix(static_cast<std::size_t>(n));
    }
    return true;
}

} // namespace

void writeFileAtomically(const std::filesystem::path& path, std::string_view content) {
    writeFileAtomically(path, [content](const PieceSink& sink) { sink(content); });
}

void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const PieceSink&)>& produce) {
    // The temporary sits in the target's directory (a rename does not cross file systems) and
    // carries the process id, so that two writers never share one.
    const std::filesystem::path temporary =
        path.parent_path() /
        ("." + path.filename().string() + ".partial-" + std::to_string(::getpid()));
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) throwIoError("write", path, errno);
    int err = 0;
    try {
        produce([&](std::string_view piece) {
            if (err == 0 && !writeAll(fd, piece)) err = errno;
        });
    } catch (...) {
        ::close(fd);
        ::unlink(temporary.c_str());
        throw;
    }
    if (err == 0 && ::fsync(fd) != 0) err = errno;
    if (::close(fd) != 0 && err == 0) err = errno;
    if (err == 0 && ::rename(temporary.c_str(), path.c_str()) != 0) err = errno;
    if (err != 0) {
        ::unlink(temporary.c_str());
        throwIoError("write", path, err);
    }
}

std::string readWholeFile(const std::filesystem::path& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throwIoError("read", path, errno);
    struct stat st {};
    if (::fstat(fd, &st) == 0 && S_ISDIR(st.st_mode)) {
        ::close(fd);
        throwIoError("read", path, EISDIR);
    }
    std::string content;
    char buffer[1 << 16];
    while (true) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n < 0) {
            if (errno == EINTR) continue;
            const int err = errno;
            ::close(fd);
            throwIoError("read", path, err);
        }
        if (n == 0) break;
        content.append(buffer, static_cast<std::size_t>(n));
    }
    ::close(fd);
    return content;
}

AppendFile::AppendFile(const std::filesystem::path& path, std::int64_t truncateTo) : path_(path) {
    fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throwIoError("open", path, errno);
    struct stat st {};
    if (::fstat(fd_, &st) != 0) {
        const int err = errno;
        close();
        throwIoError("open", path, err);
    }
    size_ = st.st_size;
    if (truncateTo >= 0) {
        if (truncateTo > size_) {
            close();
            throw IoError(path.string() + " is shorter (" + std::to_string(st.st_size) +
                          " bytes) than its restart point (" + std::to_string(truncateTo) +
                          " bytes): it was changed after the restart file was written");
        }
        if (::ftruncate(fd_, truncateTo) != 0) {
            const int err = errno;
            close();
            throwIoError("truncate", path, err);
        }
        size_ = truncateTo;
    }
    if (::lseek(fd_, size_, SEEK_SET) < 0) {
        const int err = errno;
        close();
        throwIoError("open", path, err);
    }
}

AppendFile::AppendFile(AppendFile&& other) noexcept
    : path_(std::move(other.path_)), fd_(other.fd_), size_(other.size_) {
    other.fd_ = -1;
}

AppendFile& AppendFile::operator=(AppendFile&& other) noexcept {
    if (this != &other) {
        close();
        path_ = std::move(other.path_);
        fd_ = other.fd_;
        size_ = other.size_;
        other.fd_ = -1;
    }
    return *this;
}

AppendFile::~AppendFile() {
    close();
}

void AppendFile::close() noexcept {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
}

void AppendFile::sync() {
    // A device without a disk behind it (/dev/full, a pipe) has nothing to flush.
    if (fd_ >= 0 && ::fdatasync(fd_) != 0 && errno != EINVAL && errno != EROFS)
        throwIoError("write", path_, errno);
}

void AppendFile::append(std::string_view record) {
    appendPieces([record](const PieceSink& sink) { sink(record); });
}

void AppendFile::appendPieces(const std::function<void(const PieceSink&)>& produce) {
    if (fd_ < 0) throw IoError("cannot write " + path_.string() + ": the file is not open");
    const std::int64_t start = size_;
    try {
        produce([&](std::string_view piece) {
            if (!writeAll(fd_, piece)) throwIoError("write", path_, errno);
            size_ += static_cast<std::int64_t>(piece.size());
        });
    } catch (...) {
        // Whatever part of the record reached the file is cut off again: the file keeps ending
        // on a whole record (a full device frees the space of the part it took).
        if (::ftruncate(fd_, start) == 0) ::lseek(fd_, start, SEEK_SET);
        size_ = start;
        throw;
    }
}

} // namespace terrace
