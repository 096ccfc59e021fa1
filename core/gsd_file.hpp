#pragma once
// A GSD file (version 2.0 of the file layer), written frame by frame: the format HOOMD-blue writes
// and OVITO, freud and gsd read. Written from the specification (J. A. Anderson et al., GSD file
// layer, gsd.readthedocs.io): a 256-byte header, a namelist of zero-ended chunk names, an index of
// 32-byte entries (frame, N, location, M, name id, type, flags) sorted by frame and, within a
// frame, by name id; and the chunks' data anywhere in the file.
//
// Here the namelist and a first index block follow the header and every chunk is appended at the
// end. A frame's index entries go into the block's free slots when the frame ends, the block
// moving to the end of the file at twice its size when it is full, and the header pointing to it
// last: a run stopped at any moment leaves every ended frame readable.
#include "core/output_file.hpp"
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace terrace {

/// The GSD file layer's element types.
enum class GsdType : std::uint8_t {
    UInt8 = 1,
    UInt16 = 2,
    UInt32 = 3,
    UInt64 = 4,
    Int8 = 5,
    Int16 = 6,
    Int32 = 7,
    Int64 = 8,
    Float = 9,
    Double = 10
};

/// Bytes of one element of type t.
std::size_t gsdTypeSize(GsdType t);

/// One index entry as the file holds it.
struct GsdIndexEntry {
    std::uint64_t frame = 0, n = 0;
    std::int64_t location = 0;
    std::uint32_t m = 0;
    std::uint16_t id = 0;
    GsdType type = GsdType::UInt8;
};

class GsdWriter {
public:
    /// A new file at `path` (an existing one is replaced) with these chunk names, in the order
    /// their ids follow; schema e.g. "hoomd" at version {1, 4}.
    GsdWriter(const std::filesystem::path& path, const std::string& application,
              const std::string& schema, std::uint32_t schemaMajor, std::uint32_t schemaMinor,
              const std::vector<std::string>& names);
    /// The file at `path`, written by this class with these names, keeping its first `frames`
    /// frames (a continued run drops those after its restart point); later frames follow them.
    GsdWriter(const std::filesystem::path& path, const std::vector<std::string>& names,
              std::uint64_t frames);
    GsdWriter(GsdWriter&& other) noexcept;
    GsdWriter& operator=(GsdWriter&& other) noexcept;
    GsdWriter(const GsdWriter&) = delete;
    GsdWriter& operator=(const GsdWriter&) = delete;
    ~GsdWriter();

    /// A chunk of the current frame: n rows of m elements of `type`, row-major.
    void writeChunk(const std::string& name, GsdType type, std::uint64_t n, std::uint32_t m,
                    const void* data);
    /// The same, its bytes handed over in order by `produce` to the sink it is given (a chunk too
    /// large to hold whole); they must come to n·m elements.
    void writeChunkPieces(const std::string& name, GsdType type, std::uint64_t n, std::uint32_t m,
                          const std::function<void(const PieceSink&)>& produce);
    /// Ends the current frame: its index entries (and the header, when the index moved) are
    /// written.
    void endFrame();
    /// Puts every ended frame on the disk (fdatasync): before a restart file counts them.
    void flush();
    /// Frames ended so far.
    std::uint64_t frames() const { return frames_; }
    const std::filesystem::path& path() const { return path_; }

private:
    int fd_ = -1;
    std::filesystem::path path_;
    std::vector<std::string> names_;
    std::vector<GsdIndexEntry> index_;   // every entry of ended frames
    std::vector<GsdIndexEntry> pending_; // the current frame's
    std::uint64_t frames_ = 0;
    std::int64_t end_ = 0; // where the next chunk goes
    std::int64_t indexLocation_ = 0;
    std::uint64_t indexAllocated_ = 0;

    void writeAt(std::int64_t offset, const void* data, std::size_t bytes);
    void writeHeader(const std::string& application, const std::string& schema,
                     std::uint32_t schemaVersion, std::int64_t namelistLocation,
                     std::uint64_t namelistAllocated);
    void writeIndexLocation();
    void close() noexcept;
};

/// What a GSD file holds: its header's fields and index (for tests and for reopening).
struct GsdContents {
    std::string application, schema;
    std::uint32_t schemaVersion = 0, gsdVersion = 0;
    std::vector<std::string> names;
    std::vector<GsdIndexEntry> index;
    std::int64_t indexLocation = 0;
    std::uint64_t indexAllocated = 0;
    std::int64_t namelistLocation = 0;
    std::uint64_t namelistAllocated = 0;
};

/// Reads and checks a GSD file's header, namelist and index; throws TrajectoryError naming the
/// file and what is wrong.
GsdContents readGsdContents(const std::filesystem::path& path);

/// The data of one chunk (as bytes); throws TrajectoryError if the file is short.
std::string readGsdChunk(const std::filesystem::path& path, const GsdIndexEntry& entry);

} // namespace terrace
