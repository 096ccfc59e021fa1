// Output whole or absent: the atomic write and the record-by-record append, against real faults
// (/dev/full for a full device, a file-size limit, a directory that does not exist).
#include "core/output_file.hpp"
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <gtest/gtest.h>
#include <stdexcept>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace test_output_file {

using namespace terrace;
namespace fs = std::filesystem;

namespace {

fs::path freshDirectory(const std::string& name) {
    const fs::path dir =
        fs::temp_directory_path() / ("terrace-output-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string messageOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const IoError& e) {
        return e.what();
    }
    return "";
}

/// Runs `appendRecords` on a fresh AppendFile at `path` in a child process under a 4096-byte
/// file-size limit (SIGXFSZ ignored, as the run driver does, so a write fails with EFBIG; a child,
/// so that the limit does not bind the test runner). The child's exit status: 0 when the appends
/// failed with "File too large" and the file was left at `expectedSize` bytes, 1 when no append
/// failed, 2 for another size or message, 3 when the limit could not be set.
int appendUnderFileLimit(const fs::path& path, std::int64_t expectedSize,
                         const std::function<void(AppendFile&)>& appendRecords) {
    const pid_t child = ::fork();
    if (child < 0) return -1;
    if (child == 0) {
        std::signal(SIGXFSZ, SIG_IGN);
        rlimit limit{4096, 4096};
        if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(3);
        AppendFile file(path, 0);
        try {
            appendRecords(file);
        } catch (const IoError& e) {
            const bool named = std::string(e.what()).find("File too large") != std::string::npos;
            ::_exit(file.size() == expectedSize && named ? 0 : 2);
        }
        ::_exit(1);
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

} // namespace

TEST(OutputFile, AtomicWriteReplacesTheFileAndLeavesNoTemporary) {
    const fs::path dir = freshDirectory("atomic");
    writeFileAtomically(dir / "a.json", "old\n");
    writeFileAtomically(dir / "a.json", "new content\n");
    EXPECT_EQ(readWholeFile(dir / "a.json"), "new content\n");
    int entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir))
        ++entries;
    EXPECT_EQ(entries, 1);
}

TEST(OutputFile, AFailedAtomicWriteNamesTheFileAndTheCause) {
    const fs::path missing = freshDirectory("missing") / "no-such-dir" / "summary.json";
    const std::string m = messageOf([&] { writeFileAtomically(missing, "x"); });
    EXPECT_NE(m.find("cannot write " + missing.string()), std::string::npos) << m;
    EXPECT_NE(m.find("No such file or directory"), std::string::npos) << m;
    // The target is a directory: the rename fails, the old content stays, no temporary is left.
    const fs::path dir = freshDirectory("isdir");
    fs::create_directories(dir / "summary.json" / "inside");
    EXPECT_THROW(writeFileAtomically(dir / "summary.json", "x"), IoError);
    EXPECT_TRUE(fs::is_directory(dir / "summary.json"));
    int entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir))
        ++entries;
    EXPECT_EQ(entries, 1);
}

TEST(OutputFile, AppendingToAFullDeviceIsAnError) {
    ASSERT_TRUE(fs::exists("/dev/full")); // Linux has it: a device that is always full
    AppendFile full("/dev/full", -1);
    const std::string m = messageOf([&] { full.append("a frame\n"); });
    EXPECT_NE(m.find("cannot write /dev/full: No space left on device"), std::string::npos) << m;
}

// A record that does not fit under the file-size limit is cut off again: the file ends on the
// last whole record (SIGXFSZ ignored, as the run driver does, so the write fails with EFBIG).
TEST(OutputFile, ARecordThatDoesNotFitIsCutOffAgain) {
    const fs::path dir = freshDirectory("limit");
    const std::string record(1000, 'x');
    EXPECT_EQ(appendUnderFileLimit(dir / "trajectory.xyz", 4000,
                                   [&](AppendFile& file) {
                                       for (int k = 0; k < 10; ++k)
                                           file.append(record);
                                   }),
              0)
        << "1: no error; 2: wrong size or message; 3: no limit";
    EXPECT_EQ(fs::file_size(dir / "trajectory.xyz"), 4000u);
}

TEST(OutputFile, AppendingContinuesAfterACutBackPoint) {
    const fs::path dir = freshDirectory("append");
    {
        AppendFile file(dir / "t.xyz", 0);
        file.append("one\n");
        file.append("two\n");
        EXPECT_EQ(file.size(), 8);
    }
    {
        AppendFile file(dir / "t.xyz", 4); // a continued run drops what followed its restart
        file.append("three\n");
    }
    EXPECT_EQ(readWholeFile(dir / "t.xyz"), "one\nthree\n");
    EXPECT_THROW(AppendFile(dir / "t.xyz", 1000), IoError); // the file lost its restart point
}

TEST(OutputFile, ReadingADirectoryOrAMissingFileNamesTheCause) {
    const fs::path dir = freshDirectory("read");
    EXPECT_NE(messageOf([&] { readWholeFile(dir); }).find("Is a directory"), std::string::npos);
    EXPECT_NE(messageOf([&] { readWholeFile(dir / "nothing"); }).find("No such file"),
              std::string::npos);
}

// A content handed over in pieces lands whole, and a producer that fails half way leaves the
// target as it was and no temporary beside it.
TEST(OutputFile, AtomicWriteInPiecesIsWholeOrAbsent) {
    const fs::path dir = freshDirectory("pieces");
    writeFileAtomically(dir / "f.xyz", [](const PieceSink& sink) {
        sink("2\n");
        sink("header\n");
        sink("");
        sink("X 1\nX 2\n");
    });
    EXPECT_EQ(readWholeFile(dir / "f.xyz"), "2\nheader\nX 1\nX 2\n");
    EXPECT_THROW(writeFileAtomically(dir / "f.xyz",
                                     [](const PieceSink& sink) {
                                         sink("half a frame\n");
                                         throw std::runtime_error("the frame failed");
                                     }),
                 std::runtime_error);
    EXPECT_EQ(readWholeFile(dir / "f.xyz"), "2\nheader\nX 1\nX 2\n");
    int entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir))
        ++entries;
    EXPECT_EQ(entries, 1);
}

// A record appended in pieces is cut back whole when one of its pieces fails (a file-size
// limit here) or its producer throws: the file keeps ending on a record.
TEST(OutputFile, ARecordInPiecesIsCutBackWhole) {
    const fs::path dir = freshDirectory("append-pieces");
    {
        AppendFile file(dir / "t.xyz", 0);
        file.appendPieces([](const PieceSink& sink) {
            sink("one ");
            sink("record\n");
        });
        EXPECT_THROW(file.appendPieces([](const PieceSink& sink) {
            sink("a piece that reaches the file\n");
            throw std::runtime_error("then the frame failed");
        }),
                     std::runtime_error);
        EXPECT_EQ(file.size(), 11);
        file.append("two\n");
    }
    EXPECT_EQ(readWholeFile(dir / "t.xyz"), "one record\ntwo\n");
    const std::string piece(1000, 'x');
    EXPECT_EQ(appendUnderFileLimit(dir / "limited.xyz", 1000,
                                   [&](AppendFile& file) {
                                       file.appendPieces(
                                           [&](const PieceSink& sink) { sink(piece); });
                                       file.appendPieces([&](const PieceSink& sink) {
                                           for (int k = 0; k < 5; ++k) // the fourth meets the limit
                                               sink(piece);
                                       });
                                   }),
              0)
        << "1: no error; 2: wrong size or message; 3: no limit";
    EXPECT_EQ(fs::file_size(dir / "limited.xyz"), 1000u);
}

} // namespace test_output_file
