// GSD trajectories: the file layer read back by our own reader (gsd's reader checks the same
// files in tests/cli, where python3-gsd is installed), the index growing past its first block,
// a file reopened at a restart point, and the HOOMD frame's quaternions and momenta.
#include "core/gsd_file.hpp"
#include "core/gsd_frame.hpp"
#include "core/units.hpp"
#include "core/xyz.hpp"
#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <unistd.h>

namespace test_gsd {

using namespace terrace;

namespace {

std::filesystem::path scratchDir() {
    return std::filesystem::temp_directory_path() / ("terrace-gsd-" + std::to_string(getpid()));
}

std::filesystem::path scratch(const std::string& name) {
    std::filesystem::create_directories(scratchDir());
    return scratchDir() / name;
}

/// The files the tests wrote go when they end.
class RemoveScratch : public ::testing::Environment {
public:
    void TearDown() override { std::filesystem::remove_all(scratchDir()); }
};
const auto* const removeScratch = ::testing::AddGlobalTestEnvironment(new RemoveScratch);

template <class T> std::vector<T> values(const std::filesystem::path& p, const GsdIndexEntry& e) {
    const std::string raw = readGsdChunk(p, e);
    std::vector<T> v(raw.size() / sizeof(T));
    std::memcpy(v.data(), raw.data(), raw.size());
    return v;
}

const GsdIndexEntry* find(const GsdContents& c, std::uint64_t frame, const std::string& name) {
    for (const auto& e : c.index)
        if (e.frame == frame && c.names[e.id] == name) return &e;
    return nullptr;
}

} // namespace

TEST(Gsd, FramesReadBackThroughAGrowingIndex) {
    const auto path = scratch("grow.gsd");
    const std::vector<std::string> names{"b/second", "a/first"};
    {
        GsdWriter w(path, "terrace test", "hoomd", 1, 4, names);
        // 700 frames of two chunks: 1400 entries, past the first block of 1024.
        for (std::uint64_t f = 0; f < 700; ++f) {
            const std::vector<double> a{double(f), -double(f)};
            const std::uint64_t b = f * 3;
            w.writeChunk("b/second", GsdType::UInt64, 1, 1, &b);
            w.writeChunk("a/first", GsdType::Double, 1, 2, a.data());
            w.endFrame();
        }
        EXPECT_EQ(w.frames(), 700u);
    }
    const GsdContents c = readGsdContents(path);
    EXPECT_EQ(c.schema, "hoomd");
    EXPECT_EQ(c.application, "terrace test");
    EXPECT_EQ(c.schemaVersion, (1u << 16) | 4u);
    EXPECT_EQ(c.gsdVersion, 2u << 16);
    EXPECT_EQ(c.names, names);
    ASSERT_EQ(c.index.size(), 1400u);
    EXPECT_GT(c.indexAllocated, 1400u);
    for (std::size_t k = 0; k < c.index.size(); ++k) {
        // By frame, then by name id within a frame.
        EXPECT_EQ(c.index[k].frame, k / 2);
        EXPECT_EQ(c.index[k].id, k % 2);
    }
    const auto* a = find(c, 699, "a/first");
    ASSERT_NE(a, nullptr);
    EXPECT_EQ(values<double>(path, *a), (std::vector<double>{699.0, -699.0}));
    EXPECT_EQ(values<std::uint64_t>(path, *find(c, 5, "b/second")), std::vector<std::uint64_t>{15});
}

TEST(Gsd, AReopenedFileKeepsItsFirstFramesAndGoesOn) {
    const auto path = scratch("reopen.gsd");
    const std::vector<std::string> names{"x"};
    const auto write = [&](GsdWriter& w, std::uint64_t from, std::uint64_t to) {
        for (std::uint64_t f = from; f < to; ++f) {
            const double x = 10.0 * double(f) + 1.0;
            w.writeChunk("x", GsdType::Double, 1, 1, &x);
            w.endFrame();
        }
    };
    {
        GsdWriter w(path, "t", "hoomd", 1, 4, names);
        write(w, 0, 8);
    }
    {
        // A restart point after 5 frames: frames 5..7 were written after it and go.
        GsdWriter w(path, names, 5);
        EXPECT_EQ(w.frames(), 5u);
        write(w, 5, 9);
    }
    const GsdContents c = readGsdContents(path);
    ASSERT_EQ(c.index.size(), 9u);
    for (std::uint64_t f = 0; f < 9; ++f)
        EXPECT_EQ(values<double>(path, c.index[f]), std::vector<double>{10.0 * double(f) + 1.0});
    // A restart point beyond what the file holds is refused, naming both counts.
    try {
        GsdWriter w(path, names, 12);
        FAIL() << "reopened past its end";
    } catch (const TrajectoryError& e) {
        EXPECT_NE(std::string(e.what()).find("holds 9 frames"), std::string::npos) << e.what();
    }
    // Other chunk names than the run's: refused.
    EXPECT_THROW(GsdWriter(path, std::vector<std::string>{"y"}, 1), TrajectoryError);
}

TEST(Gsd, NotAGsdFileIsRefusedWithItsCause) {
    const auto path = scratch("text.gsd");
    std::ofstream(path) << std::string(300, 'x');
    try {
        readGsdContents(path);
        FAIL();
    } catch (const TrajectoryError& e) {
        EXPECT_NE(std::string(e.what()).find("no GSD magic number"), std::string::npos);
    }
    // Cut inside its index: refused, not read past the end.
    const auto good = scratch("cut.gsd");
    { GsdWriter w(good, "t", "hoomd", 1, 4, {"x"}); }
    std::filesystem::resize_file(good, 400);
    EXPECT_THROW(readGsdContents(good), TrajectoryError);
}

TEST(Gsd, HoomdFrameOfALinearRotor) {
    Scene scene; // the default rods
    const GsdBodyType type = gsdBodyType(scene);
    EXPECT_EQ(type.shape["type"], "ConvexPolyhedron");
    Snapshot s;
    s.time = units::fromPs(1.5);
    s.boxLength = 10.0;
    const Vec3 axis = Vec3(1, 2, 2).normalized();
    const Vec3 omega = axis.unitOrthogonal() * 3.0; // rad per time unit, ⊥ axis
    s.position = {Vec3(12.0, -6.0, 4.0)};
    s.velocity = {Vec3(0.1, 0.2, 0.3)};
    s.axis = {axis};
    s.omega = {omega};
    const auto path = scratch("frame.gsd");
    {
        GsdWriter w(path, "t", "hoomd", 1, 4, hoomdChunkNames());
        writeHoomdFrame(w, s, type, 7);
    }
    const GsdContents c = readGsdContents(path);
    const auto pos = values<float>(path, *find(c, 0, "particles/position"));
    const auto img = values<std::int32_t>(path, *find(c, 0, "particles/image"));
    for (int k = 0; k < 3; ++k) {
        EXPECT_GE(pos[k], -5.0f);
        EXPECT_LT(pos[k], 5.0f);
        EXPECT_NEAR(pos[k] + 10.0 * img[k], s.position[0][k], 1e-5);
    }
    const auto q = values<float>(path, *find(c, 0, "particles/orientation"));
    const Quat qd(q[0], q[1], q[2], q[3]);
    EXPECT_NEAR((qd * Vec3::UnitZ() - axis).norm(), 0.0, 1e-6);
    // L_body back from p: ½ (q* ⊗ p).vec, and in the lab it is I ω for a rotor spun ⊥ its axis.
    const auto p = values<float>(path, *find(c, 0, "particles/angmom"));
    const Quat pq(p[0], p[1], p[2], p[3]);
    const Quat lb = qd.conjugate() * pq;
    const Vec3 lBody = 0.5 * Vec3(lb.x(), lb.y(), lb.z());
    const Vec3 lLab = qd * lBody;
    const Vec3 expected = scene.body.inertia.x() * omega / units::psPerTimeUnit;
    EXPECT_NEAR((lLab - expected).norm(), 0.0, 1e-5 * expected.norm());
    EXPECT_NEAR(lb.w(), 0.0, 1e-5);
    EXPECT_EQ(values<std::uint64_t>(path, *find(c, 0, "configuration/step")),
              std::vector<std::uint64_t>{7});
    EXPECT_EQ(values<double>(path, *find(c, 0, "log/time_ps")), std::vector<double>{1.5});
    const auto v = values<float>(path, *find(c, 0, "particles/velocity"));
    EXPECT_NEAR(v[2], 0.3 / units::psPerTimeUnit, 1e-5);
}

TEST(Gsd, AFrameWrittenInPiecesEqualsOneWrittenWhole) {
    Scene scene;
    scene.potential.kind = "gay-berne";
    const GsdBodyType type = gsdBodyType(scene);
    EXPECT_EQ(type.shape["type"], "Ellipsoid");
    Snapshot s;
    s.boxLength = 8.0;
    for (int i = 0; i < 5; ++i) {
        s.position.push_back(Vec3(1.7 * i - 4.0, 9.0 * i, -3.9 + i));
        s.velocity.push_back(Vec3(i, -i, 0.5));
        s.axis.push_back(Vec3(1.0, i, 2.0).normalized());
        s.omega.push_back(s.axis.back().unitOrthogonal() * i);
    }
    const auto whole = scratch("whole.gsd"), pieces = scratch("pieces.gsd");
    {
        GsdWriter w(whole, "t", "hoomd", 1, 4, hoomdChunkNames());
        writeHoomdFrame(w, s, type, 0);
    }
    {
        GsdWriter w(pieces, "t", "hoomd", 1, 4, hoomdChunkNames());
        const auto bodiesOf = [&s](int begin, int end) {
            Snapshot p;
            p.position.assign(s.position.begin() + begin, s.position.begin() + end);
            p.velocity.assign(s.velocity.begin() + begin, s.velocity.begin() + end);
            p.axis.assign(s.axis.begin() + begin, s.axis.begin() + end);
            p.omega.assign(s.omega.begin() + begin, s.omega.begin() + end);
            return p;
        };
        writeHoomdFrame(w, s.size(), s.time, s.boxLength, bodiesOf, type, 0, 2);
    }
    const GsdContents a = readGsdContents(whole), b = readGsdContents(pieces);
    ASSERT_EQ(a.index.size(), b.index.size());
    for (std::size_t k = 0; k < a.index.size(); ++k)
        EXPECT_EQ(readGsdChunk(whole, a.index[k]), readGsdChunk(pieces, b.index[k]))
            << a.names[a.index[k].id];
}

TEST(Gsd, FramesReadBackAsTheSnapshotsWritten) {
    // A linear rotor (default rods) and an asymmetric top: positions unwrapped again, axes,
    // orientations and angular velocities back to GSD's single precision.
    for (const bool top : {false, true}) {
        Scene scene;
        if (top) scene.body.kind = "asymmetric", scene.body.inertia = Vec3(1.0, 2.0, 3.0);
        const GsdBodyType type = gsdBodyType(scene);
        const auto path = scratch(top ? "top.gsd" : "rotor.gsd");
        std::vector<Snapshot> written;
        {
            GsdWriter w(path, "t", "hoomd", 1, 4, hoomdChunkNames());
            for (int f = 0; f < 3; ++f) {
                Snapshot s;
                s.time = units::fromPs(0.009 * f);
                s.boxLength = 12.0;
                for (int i = 0; i < 4; ++i) {
                    s.position.push_back(Vec3(5.9 * i - 20.0 + f, 0.3 * i, 13.0 * f));
                    s.velocity.push_back(Vec3(0.01 * i, -0.02, 0.03 * f));
                    const Quat q = Quat(1.0, 0.1 * i, -0.2, 0.3 * f).normalized();
                    s.axis.push_back(q * Vec3::UnitZ());
                    if (top) s.orientation.push_back(q);
                    const Vec3 w(0.2 * i, -0.1, 0.05);
                    // A linear rotor spins only ⊥ its axis.
                    s.omega.push_back(top ? w : w - w.dot(s.axis.back()) * s.axis.back());
                }
                writeHoomdFrame(w, s, type, std::uint64_t(f));
                written.push_back(s);
            }
        }
        std::vector<Snapshot> read;
        EXPECT_EQ(forEachGsdFrame(path, [&](Snapshot&& s) { read.push_back(std::move(s)); }), 3);
        ASSERT_EQ(read.size(), 3u);
        for (int f = 0; f < 3; ++f) {
            const Snapshot &a = written[f], &b = read[f];
            EXPECT_NEAR(b.time, a.time, 1e-12);
            EXPECT_EQ(b.boxLength, 12.0);
            ASSERT_EQ(b.size(), a.size());
            EXPECT_EQ(b.orientation.size(), a.orientation.size());
            for (int i = 0; i < a.size(); ++i) {
                EXPECT_NEAR((b.position[i] - a.position[i]).norm(), 0.0, 1e-5);
                EXPECT_NEAR((b.velocity[i] - a.velocity[i]).norm(), 0.0, 1e-7);
                EXPECT_NEAR((b.axis[i] - a.axis[i]).norm(), 0.0, 1e-6);
                EXPECT_NEAR((b.omega[i] - a.omega[i]).norm(), 0.0, 1e-6) << "frame " << f;
            }
        }
    }
}

} // namespace test_gsd
