#include "core/gsd_file.hpp"
#include "core/output_file.hpp"
#include "core/xyz.hpp"
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

namespace terrace {

namespace {

constexpr std::uint64_t gsdMagic = 0x65DF65DF65DF65DFull;
constexpr std::uint32_t gsdVersion = 2u << 16; // file layer 2.0
constexpr std::size_t headerBytes = 256, entryBytes = 32, nameBytes = 64;
constexpr std::uint64_t namelistSlots = 64;     // our few names, with room
constexpr std::uint64_t firstIndexSlots = 1024; // grows by doubling at the end of the file

// Header fields' offsets (all little-endian, as on every machine this runs on).
constexpr std::size_t offMagic = 0, offIndexLocation = 8, offIndexAllocated = 16,
                      offNamelistLocation = 24, offNamelistAllocated = 32, offSchemaVersion = 40,
                      offGsdVersion = 44, offApplication = 48, offSchema = 112;

template <class T> void put(std::string& bytes, std::size_t at, T value) {
    std::memcpy(bytes.data() + at, &value, sizeof value);
}
template <class T> T get(const std::string& bytes, std::size_t at) {
    T value;
    std::memcpy(&value, bytes.data() + at, sizeof value);
    return value;
}

std::string encodeEntry(const GsdIndexEntry& e) {
    std::string b(entryBytes, '\0');
    put(b, 0, e.frame);
    put(b, 8, e.n);
    put(b, 16, e.location);
    put(b, 24, e.m);
    put(b, 28, e.id);
    put(b, 30, static_cast<std::uint8_t>(e.type));
    return b; // flags (byte 31) stay 0
}

std::string encodeEntries(const std::vector<GsdIndexEntry>& entries) {
    std::string b;
    b.reserve(entries.size() * entryBytes);
    for (const auto& e : entries)
        b += encodeEntry(e);
    return b;
}

std::string readAt(int fd, const std::filesystem::path& path, std::int64_t offset,
                   std::size_t bytes) {
    std::string b(bytes, '\0');
    std::size_t done = 0;
    while (done < bytes) {
        const ssize_t n = ::pread(fd, b.data() + done, bytes - done, offset + done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throwIoError("read", path, errno);
        if (n == 0)
            throw TrajectoryError(path.string() + ": not a GSD file written whole (it ends at " +
                                  std::to_string(offset + done) + " bytes, inside a block)");
        done += std::size_t(n);
    }
    return b;
}

/// A file open for reading, closed when it goes out of scope; IoError naming it if it cannot be
/// opened.
struct ReadOnlyFile {
    int fd;
    explicit ReadOnlyFile(const std::filesystem::path& path)
        : fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC)) {
        if (fd < 0) throwIoError("open", path, errno);
    }
    ReadOnlyFile(const ReadOnlyFile&) = delete;
    ReadOnlyFile& operator=(const ReadOnlyFile&) = delete;
    ~ReadOnlyFile() { ::close(fd); }
};

bool validType(std::uint8_t t) {
    return t >= 1 && t <= 10;
}

} // namespace

std::size_t gsdTypeSize(GsdType t) {
    switch (t) {
    case GsdType::UInt8:
    case GsdType::Int8:
        return 1;
    case GsdType::UInt16:
    case GsdType::Int16:
        return 2;
    case GsdType::UInt32:
    case GsdType::Int32:
    case GsdType::Float:
        return 4;
    case GsdType::UInt64:
    case GsdType::Int64:
    case GsdType::Double:
        return 8;
    }
    return 0;
}

GsdWriter::GsdWriter(const std::filesystem::path& path, const std::string& application,
                     const std::string& schema, std::uint32_t schemaMajor,
                     std::uint32_t schemaMinor, const std::vector<std::string>& names)
    : path_(path), names_(names) {
    if (names.size() > namelistSlots) throw std::logic_error("GsdWriter: too many chunk names");
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd_ < 0) throwIoError("create", path, errno);
    const std::int64_t namelistLocation = headerBytes;
    // File layer 2: the names one after the other, each ended by a zero byte (an empty name ends
    // the list), in a block of 64 bytes per allocated entry.
    std::string namelist;
    for (const auto& name : names) {
        if (name.empty() || name.size() >= nameBytes || name.find('\0') != std::string::npos)
            throw std::logic_error("GsdWriter: a chunk name of 1 to 63 bytes");
        namelist += name;
        namelist += '\0';
    }
    namelist.resize(namelistSlots * nameBytes, '\0');
    writeAt(namelistLocation, namelist.data(), namelist.size());
    indexLocation_ = namelistLocation + std::int64_t(namelist.size());
    indexAllocated_ = firstIndexSlots;
    const std::string index(indexAllocated_ * entryBytes, '\0');
    writeAt(indexLocation_, index.data(), index.size());
    end_ = indexLocation_ + std::int64_t(index.size());
    writeHeader(application, schema, (schemaMajor << 16) | schemaMinor, namelistLocation,
                namelistSlots);
}

GsdWriter::GsdWriter(const std::filesystem::path& path, const std::vector<std::string>& names,
                     std::uint64_t frames)
    : path_(path), names_(names) {
    const GsdContents c = readGsdContents(path);
    if (c.names != names)
        throw TrajectoryError(path.string() + ": its chunk names are not those this run writes");
    fd_ = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
    if (fd_ < 0) throwIoError("open", path, errno);
    for (const auto& e : c.index)
        if (e.frame < frames) index_.push_back(e);
    frames_ = index_.empty() ? 0 : index_.back().frame + 1;
    if (frames_ != frames)
        throw TrajectoryError(path.string() + " holds " + std::to_string(frames_) +
                              " frames, fewer than the " + std::to_string(frames) +
                              " its restart file counts");
    indexLocation_ = c.indexLocation;
    indexAllocated_ = c.indexAllocated;
    // The dropped frames' entries are cleared (the block ends at its first empty entry); their
    // data stays in the file, unreferenced, and new chunks go after everything.
    const std::string cleared((indexAllocated_ - index_.size()) * entryBytes, '\0');
    writeAt(indexLocation_ + std::int64_t(index_.size() * entryBytes), cleared.data(),
            cleared.size());
    const off_t size = ::lseek(fd_, 0, SEEK_END);
    if (size < 0) throwIoError("read", path, errno);
    end_ = size;
    if (::fdatasync(fd_) != 0) throwIoError("write", path, errno);
}

GsdWriter::GsdWriter(GsdWriter&& o) noexcept
    : fd_(o.fd_), path_(std::move(o.path_)), names_(std::move(o.names_)),
      index_(std::move(o.index_)), pending_(std::move(o.pending_)), frames_(o.frames_),
      end_(o.end_), indexLocation_(o.indexLocation_), indexAllocated_(o.indexAllocated_) {
    o.fd_ = -1;
}

GsdWriter& GsdWriter::operator=(GsdWriter&& o) noexcept {
    if (this != &o) {
        close();
        fd_ = o.fd_;
        o.fd_ = -1;
        path_ = std::move(o.path_);
        names_ = std::move(o.names_);
        index_ = std::move(o.index_);
        pending_ = std::move(o.pending_);
        frames_ = o.frames_;
        end_ = o.end_;
        indexLocation_ = o.indexLocation_;
        indexAllocated_ = o.indexAllocated_;
    }
    return *this;
}

GsdWriter::~GsdWriter() {
    close();
}

void GsdWriter::close() noexcept {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
}

void GsdWriter::writeAt(std::int64_t offset, const void* data, std::size_t bytes) {
    const char* p = static_cast<const char*>(data);
    std::size_t done = 0;
    while (done < bytes) {
        const ssize_t n = ::pwrite(fd_, p + done, bytes - done, offset + done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throwIoError("write", path_, errno);
        done += std::size_t(n);
    }
}

void GsdWriter::writeHeader(const std::string& application, const std::string& schema,
                            std::uint32_t schemaVersion, std::int64_t namelistLocation,
                            std::uint64_t namelistAllocated) {
    std::string h(headerBytes, '\0');
    put(h, offMagic, gsdMagic);
    put(h, offIndexLocation, std::uint64_t(indexLocation_));
    put(h, offIndexAllocated, indexAllocated_);
    put(h, offNamelistLocation, std::uint64_t(namelistLocation));
    put(h, offNamelistAllocated, namelistAllocated);
    put(h, offSchemaVersion, schemaVersion);
    put(h, offGsdVersion, gsdVersion);
    std::memcpy(h.data() + offApplication, application.data(),
                std::min<std::size_t>(63, application.size()));
    std::memcpy(h.data() + offSchema, schema.data(), std::min<std::size_t>(63, schema.size()));
    writeAt(0, h.data(), h.size());
}

void GsdWriter::writeIndexLocation() {
    std::string b(16, '\0');
    put(b, 0, std::uint64_t(indexLocation_));
    put(b, 8, indexAllocated_);
    writeAt(offIndexLocation, b.data(), b.size());
}

void GsdWriter::writeChunk(const std::string& name, GsdType type, std::uint64_t n, std::uint32_t m,
                           const void* data) {
    const std::size_t bytes = n * m * gsdTypeSize(type);
    writeChunkPieces(name, type, n, m, [&](const PieceSink& sink) {
        sink(std::string_view(static_cast<const char*>(data), bytes));
    });
}

void GsdWriter::writeChunkPieces(const std::string& name, GsdType type, std::uint64_t n,
                                 std::uint32_t m,
                                 const std::function<void(const PieceSink&)>& produce) {
    const auto it = std::find(names_.begin(), names_.end(), name);
    if (it == names_.end()) throw std::logic_error("GsdWriter: unknown chunk " + name);
    if (n == 0 || m == 0) throw std::logic_error("GsdWriter: an empty chunk " + name);
    const std::size_t bytes = n * m * gsdTypeSize(type);
    std::size_t written = 0;
    produce([&](std::string_view piece) {
        if (written + piece.size() > bytes)
            throw std::logic_error("GsdWriter: chunk " + name + " longer than n·m elements");
        writeAt(end_ + std::int64_t(written), piece.data(), piece.size());
        written += piece.size();
    });
    if (written != bytes)
        throw std::logic_error("GsdWriter: chunk " + name + " shorter than n·m elements");
    GsdIndexEntry e;
    e.frame = frames_;
    e.n = n;
    e.m = m;
    e.location = end_;
    e.id = static_cast<std::uint16_t>(it - names_.begin());
    e.type = type;
    pending_.push_back(e);
    end_ += std::int64_t(bytes);
}

void GsdWriter::endFrame() {
    // Readers search a frame's entries by name id.
    std::sort(pending_.begin(), pending_.end(),
              [](const GsdIndexEntry& a, const GsdIndexEntry& b) { return a.id < b.id; });
    // The data first, then the entries that point to it, then (when it moved) the header: in
    // that order through the page cache, so that a process stopped at any point leaves ended
    // frames readable (flush() puts them on the disk).
    const std::size_t used = index_.size();
    index_.insert(index_.end(), pending_.begin(), pending_.end());
    if (index_.size() < indexAllocated_) { // room in place (one empty entry ends the block)
        const std::string entries = encodeEntries(pending_);
        writeAt(indexLocation_ + std::int64_t(used * entryBytes), entries.data(), entries.size());
    } else {
        std::uint64_t slots = indexAllocated_;
        while (slots <= index_.size())
            slots *= 2;
        std::string block = encodeEntries(index_);
        block.resize(slots * entryBytes, '\0');
        const std::int64_t at = end_;
        writeAt(at, block.data(), block.size());
        end_ += std::int64_t(block.size());
        indexLocation_ = at;
        indexAllocated_ = slots;
        writeIndexLocation();
    }
    pending_.clear();
    ++frames_;
}

void GsdWriter::flush() {
    if (::fdatasync(fd_) != 0) throwIoError("write", path_, errno);
}

GsdContents readGsdContents(const std::filesystem::path& path) {
    const ReadOnlyFile file(path);
    const int fd = file.fd;
    const off_t size = ::lseek(fd, 0, SEEK_END);
    if (size < 0) throwIoError("read", path, errno);
    const auto bad = [&](const std::string& what) {
        return TrajectoryError(path.string() + ": not a GSD file this program can read: " + what);
    };
    if (size < off_t(headerBytes)) throw bad("shorter than a header");
    const std::string h = readAt(fd, path, 0, headerBytes);
    if (get<std::uint64_t>(h, offMagic) != gsdMagic) throw bad("no GSD magic number");
    GsdContents c;
    c.gsdVersion = get<std::uint32_t>(h, offGsdVersion);
    if (c.gsdVersion >> 16 != 2) throw bad("file layer version other than 2");
    c.schemaVersion = get<std::uint32_t>(h, offSchemaVersion);
    c.application =
        std::string(h.data() + offApplication, ::strnlen(h.data() + offApplication, 64));
    c.schema = std::string(h.data() + offSchema, ::strnlen(h.data() + offSchema, 64));
    c.indexLocation = std::int64_t(get<std::uint64_t>(h, offIndexLocation));
    c.indexAllocated = get<std::uint64_t>(h, offIndexAllocated);
    c.namelistLocation = std::int64_t(get<std::uint64_t>(h, offNamelistLocation));
    c.namelistAllocated = get<std::uint64_t>(h, offNamelistAllocated);
    const auto inside = [&](std::int64_t at, std::uint64_t count, std::size_t each) {
        return at >= std::int64_t(headerBytes) && count > 0 && count < (std::uint64_t(1) << 40) &&
               std::uint64_t(at) + count * each <= std::uint64_t(size);
    };
    if (!inside(c.namelistLocation, c.namelistAllocated, nameBytes))
        throw bad("its namelist lies outside the file");
    if (!inside(c.indexLocation, c.indexAllocated, entryBytes))
        throw bad("its index lies outside the file");
    const std::string names = readAt(fd, path, c.namelistLocation, c.namelistAllocated * nameBytes);
    for (std::size_t at = 0; at < names.size();) {
        const std::size_t end = names.find('\0', at);
        if (end == at || end == std::string::npos) break;
        c.names.push_back(names.substr(at, end - at));
        at = end + 1;
    }
    const std::string index = readAt(fd, path, c.indexLocation, c.indexAllocated * entryBytes);
    for (std::uint64_t k = 0; k < c.indexAllocated; ++k) {
        const std::string raw = index.substr(k * entryBytes, entryBytes);
        GsdIndexEntry e;
        e.location = get<std::int64_t>(raw, 16);
        if (e.location == 0) break;
        e.frame = get<std::uint64_t>(raw, 0);
        e.n = get<std::uint64_t>(raw, 8);
        e.m = get<std::uint32_t>(raw, 24);
        e.id = get<std::uint16_t>(raw, 28);
        const auto type = get<std::uint8_t>(raw, 30);
        if (!validType(type) || e.m == 0 || e.id >= c.names.size() || get<std::uint8_t>(raw, 31))
            throw bad("index entry " + std::to_string(k) + " is malformed");
        e.type = static_cast<GsdType>(type);
        if (!c.index.empty() && e.frame < c.index.back().frame)
            throw bad("its index is not in frame order");
        const std::uint64_t bytes = e.n * e.m * gsdTypeSize(e.type);
        if (e.location < 0 || e.n > (std::uint64_t(1) << 40) ||
            std::uint64_t(e.location) + bytes > std::uint64_t(size))
            throw bad("chunk " + c.names[e.id] + " of frame " + std::to_string(e.frame) +
                      " lies outside the file");
        c.index.push_back(e);
    }
    return c;
}

std::string readGsdChunk(const std::filesystem::path& path, const GsdIndexEntry& entry) {
    const ReadOnlyFile file(path);
    const int fd = file.fd;
    return readAt(fd, path, entry.location, entry.n * entry.m * gsdTypeSize(entry.type));
}

} // namespace terrace
