// Extended XYZ round trip for every layout, and clear errors for malformed files.
#include "core/initial_state.hpp"
#include "core/linear_rotor.hpp"
#include "core/lj_mixture.hpp"
#include "core/scene_json.hpp"
#include "core/snapshot.hpp"
#include "core/species_sphere.hpp"
#include "core/sphere.hpp"
#include "core/symmetric_top.hpp"
#include "core/xyz.hpp"
#include "tests/mixture_scene.hpp"
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>

namespace test_xyz {

using namespace terrace;

namespace {

constexpr double conversionRoundOff = 1e-15; // relative: one multiply and one divide by 10
constexpr double printedUnitTol = 1e-15;     // a unit axis printed with 17 digits and read back

std::filesystem::path tempFile(const std::string& name) {
    return std::filesystem::temp_directory_path() / ("terrace-" + name);
}

template <class K, class P> void roundTrip(const System<K, P>& sys, const std::string& name) {
    const auto path = tempFile(name);
    const Snapshot a = makeSnapshot(sys, 0.25), b = makeSnapshot(sys, 0.5);
    {
        std::ofstream out(path);
        writeXyzFrame(out, a, layoutFor(K::rotationalDof));
        writeXyzFrame(out, b, layoutFor(K::rotationalDof));
    }
    const auto frames = readTrajectory(path.string());
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_NEAR(frames[1].time, 0.5, conversionRoundOff);
    EXPECT_EQ(frames[0].boxLength, sys.box.length);
    for (int i = 0; i < a.size(); ++i) {
        EXPECT_EQ(frames[0].position[i], a.position[i]);
        EXPECT_LE((frames[0].velocity[i] - a.velocity[i]).norm(),
                  conversionRoundOff * a.velocity[i].norm());
        EXPECT_LE((frames[0].omega[i] - a.omega[i]).norm(),
                  conversionRoundOff * (1 + a.omega[i].norm()));
        EXPECT_LE((frames[0].axis[i] - a.axis[i]).norm(), printedUnitTol);
    }
}

} // namespace

TEST(Xyz, RoundTripRods) {
    const Scene scene = defaultScene();
    roundTrip(buildInitialState<LinearRotor>(scene, rodPotential(scene)), "rods.xyz");
}

TEST(Xyz, RoundTripTopsAndSpheres) {
    Scene scene = defaultScene();
    scene.state.n = 27;
    scene.body.inertia = Vec3(1.0, 1.0, 0.4);
    roundTrip(buildInitialState<SymmetricTop>(scene, rodPotential(scene)), "tops.xyz");
    scene.potential.kind = "lj";
    scene.body.kind = "sphere";
    roundTrip(buildInitialState<Sphere>(scene, ljPotential(scene)), "spheres.xyz");
}

TEST(Xyz, HeaderIsOvitoExtendedXyz) {
    const Scene scene = defaultScene();
    const auto sys = buildInitialState<LinearRotor>(scene, rodPotential(scene));
    std::ostringstream out;
    writeXyzFrame(out, makeSnapshot(sys, 0.1), TrajectoryLayout::Rod);
    std::istringstream in(out.str());
    std::string count, header, body;
    std::getline(in, count);
    std::getline(in, header);
    std::getline(in, body);
    EXPECT_EQ(count, "512");
    EXPECT_NE(header.find("Lattice=\""), std::string::npos);
    EXPECT_NE(header.find("Properties=species:S:1:pos:R:3:velo:R:3:axis:R:3:omega:R:3:body:I:1 "),
              std::string::npos);
    EXPECT_NE(header.find("Time=10 "), std::string::npos); // 0.1 time units = 10 fs
    // A time on the sample grid as the decimal it is, without its binary round-off: 20 samples
    // of 9 fs summed in internal units is 1.8000000000000003 units, shown as 180 fs.
    double t = 0.0;
    for (int k = 0; k < 20; ++k)
        t += units::fromFs(9.0);
    ASSERT_NE(units::toFs(t), 180.0);
    Snapshot late = makeSnapshot(sys, t);
    const std::string lateText = formatXyzFrame(late, TrajectoryLayout::Rod);
    EXPECT_NE(lateText.find(" Time=180 "), std::string::npos) << lateText.substr(0, 200);
    // Species X (a dummy element to ASE, which takes the column for elements), the kind in the
    // body column at the end: its rotational degrees of freedom.
    EXPECT_EQ(body.substr(0, 2), "X ");
    EXPECT_EQ(body.substr(body.size() - 2), " 2");
}

// The species is X for every kind and the body column names the kind.
TEST(Xyz, EveryKindIsSpeciesXWithItsBodyColumn) {
    Snapshot f;
    f.boxLength = 10.0;
    f.position = {Vec3(1, 2, 3)};
    f.velocity = {Vec3(0.01, 0.02, 0.03)};
    f.axis = {Vec3::UnitZ()};
    f.omega = {Vec3(0.1, 0.0, 0.0)};
    f.orientation = {Quat::Identity()};
    const std::pair<TrajectoryLayout, std::string> kinds[] = {
        {TrajectoryLayout::Sphere, "Properties=species:S:1:pos:R:3:velo:R:3:body:I:1 "},
        {TrajectoryLayout::Rod,
         "Properties=species:S:1:pos:R:3:velo:R:3:axis:R:3:omega:R:3:body:I:1 "},
        {TrajectoryLayout::Top,
         "Properties=species:S:1:pos:R:3:velo:R:3:orientation:R:4:omega:R:3:body:I:1 "}};
    const std::string codes[] = {"0", "2", "3"};
    for (int k = 0; k < 3; ++k) {
        const std::string text = formatXyzFrame(f, kinds[k].first);
        EXPECT_NE(text.find(kinds[k].second), std::string::npos) << text;
        const std::string line = text.substr(text.rfind('\n', text.size() - 2) + 1);
        EXPECT_EQ(line.substr(0, 2), "X ") << line;
        EXPECT_EQ(line.substr(line.size() - 3), " " + codes[k] + "\n") << line;
    }
}

// Bodies begin … end−1 of a snapshot, as the engine hands a piece of a frame to the writer.
std::function<Snapshot(int, int)> pieceOf(const Snapshot& frame) {
    return [&frame](int begin, int end) {
        Snapshot piece = frame;
        auto cut = [&](auto& v) {
            if (v.empty()) return;
            v.erase(v.begin() + end, v.end());
            v.erase(v.begin(), v.begin() + begin);
        };
        cut(piece.position), cut(piece.velocity), cut(piece.axis), cut(piece.omega);
        cut(piece.orientation), cut(piece.species);
        return piece;
    };
}

// A frame written in pieces (initial.xyz, trajectory frames of large systems) is the same bytes
// as the frame written whole, whatever the piece size and layout.
TEST(Xyz, AFrameInPiecesIsTheFrameWhole) {
    Scene scene = defaultScene();
    scene.state.n = 27;
    const Snapshot rods =
        makeSnapshot(buildInitialState<LinearRotor>(scene, rodPotential(scene)), 0.3);
    scene.body.inertia = Vec3(1.0, 1.0, 0.4);
    const Snapshot tops =
        makeSnapshot(buildInitialState<SymmetricTop>(scene, rodPotential(scene)), 0.3);
    const std::pair<const Snapshot*, TrajectoryLayout> frames[] = {
        {&rods, TrajectoryLayout::Rod},
        {&rods, TrajectoryLayout::Sphere},
        {&tops, TrajectoryLayout::Top}};
    for (const auto& [frame, layout] : frames)
        for (const int perPiece : {1, 4, 26, 27, 1000}) {
            // Each piece's bodies made only when it is written.
            std::string pieces;
            int count = 0;
            writeXyzFramePieces(
                frame->size(), frame->time, frame->boxLength, layout, pieceOf(*frame),
                [&](std::string_view piece) {
                    pieces += piece;
                    ++count;
                },
                perPiece);
            EXPECT_EQ(pieces, formatXyzFrame(*frame, layout)) << perPiece;
            EXPECT_EQ(count, 1 + (27 + perPiece - 1) / perPiece) << perPiece; // header first
        }
    EXPECT_THROW(writeXyzFramePieces(
                     rods.size(), rods.time, rods.boxLength, TrajectoryLayout::Rod, pieceOf(rods),
                     [](std::string_view) {}, 0),
                 std::invalid_argument);
}

// A mixture's bodies carry their species' index in a last column, species_index, which reads
// back (a plain scene's frames have no such column: EveryKindIsSpeciesXWithItsBodyColumn); the
// element column stays X (ASE takes it for elements). Written in pieces, the frame is
// the same bytes as whole: the header, written before any piece, names the column.
TEST(Xyz, AMixtureCarriesEachBodysSpeciesIndex) {
    const Scene scene =
        sceneFromJson(terrace::mixture_tests::kobAndersen(32, 0.1, 2.0), "mixture.json");
    const auto sys = buildInitialState<SpeciesSphere>(scene, ljMixture(scene));
    const Snapshot frame = makeSnapshot(sys, 0.2);
    ASSERT_EQ(frame.species.size(), 32u);
    const std::string text = formatXyzFrame(frame, TrajectoryLayout::Sphere);
    EXPECT_NE(text.find("Properties=species:S:1:pos:R:3:velo:R:3:body:I:1:species_index:I:1 "),
              std::string::npos)
        << text.substr(0, 200);
    const std::string last = text.substr(text.rfind('\n', text.size() - 2) + 1);
    EXPECT_EQ(last.substr(0, 2), "X ");
    EXPECT_EQ(last.substr(last.size() - 5), " 0 " + std::to_string(frame.species.back()) + "\n");
    std::string pieces;
    writeXyzFramePieces(
        frame.size(), frame.time, frame.boxLength, TrajectoryLayout::Sphere, pieceOf(frame),
        [&](std::string_view piece) { pieces += piece; }, 5);
    EXPECT_EQ(pieces, text);
    const auto path = tempFile("mixture.xyz");
    std::ofstream(path) << text << text;
    const auto frames = readTrajectory(path.string());
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_EQ(frames[1].species, frame.species);
    int ofB = 0; // Kob–Andersen's 20 % of B
    for (const auto s : frame.species)
        ofB += s == 1;
    EXPECT_GT(ofB, 0);
    EXPECT_LT(ofB, 32);
    // An index below 0 is no species.
    std::string bad = text;
    bad.replace(bad.size() - 2, 1, "-1");
    std::ofstream(path) << bad;
    EXPECT_THROW(readTrajectory(path.string()), TrajectoryError);
}

// Files written before the body column (species S, R, T) still read, `terrace analyse` on old
// output included; a body column that disagrees with the layout is an error.
TEST(Xyz, FilesWithoutTheBodyColumnStillRead) {
    const auto path = tempFile("legacy.xyz");
    std::ofstream(path)
        << "2\nLattice=\"10 0 0 0 10 0 0 0 10\" "
           "Properties=species:S:1:pos:R:3:velo:R:3:axis:R:3:omega:R:3 Time=9 pbc=\"T T T\"\n"
           "R 1 2 3 10 0 0 0 0 1 0 0 0\nR 4 5 6 0 10 0 1 0 0 0 0 0\n"
           "1\nLattice=\"10 0 0 0 10 0 0 0 10\" "
           "Properties=species:S:1:pos:R:3:velo:R:3:orientation:R:4:omega:R:3 Time=18\n"
           "T 1 2 3 0 0 0 1 0 0 0 0 0 0\n"
           "1\nLattice=\"10 0 0 0 10 0 0 0 10\" Properties=species:S:1:pos:R:3:velo:R:3 Time=27\n"
           "S 7 8 9 0 0 0\n";
    const auto frames = readTrajectory(path.string());
    ASSERT_EQ(frames.size(), 3u);
    EXPECT_EQ(frames[0].position[1], Vec3(4, 5, 6));
    EXPECT_EQ(frames[0].axis[1], Vec3::UnitX());
    EXPECT_EQ(frames[1].axis[0], Vec3::UnitZ());
    EXPECT_EQ(frames[2].position[0], Vec3(7, 8, 9));
    std::ofstream(path) << "1\nLattice=\"10 0 0 0 10 0 0 0 10\" "
                           "Properties=species:S:1:pos:R:3:velo:R:3:body:I:1 Time=0\n"
                           "X 1 2 3 0 0 0 2\n";
    try {
        readTrajectory(path.string());
        FAIL() << "expected a TrajectoryError";
    } catch (const TrajectoryError& e) {
        EXPECT_NE(std::string(e.what()).find(":3: malformed body line"), std::string::npos)
            << e.what();
    }
}

TEST(Xyz, MalformedFilesAreNamedErrors) {
    const auto path = tempFile("bad.xyz");
    std::ofstream(path)
        << "2\nLattice=\"1 0 0 0 1 0 0 0 1\" Properties=species:S:1:pos:R:3:velo:R:3"
           " Time=0\nS 0 0 0 0 0 0\n";
    try {
        readTrajectory(path.string());
        FAIL() << "expected a TrajectoryError";
    } catch (const TrajectoryError& e) {
        EXPECT_NE(std::string(e.what()).find("frame ends early"), std::string::npos);
    }
    EXPECT_THROW(readTrajectory("/nonexistent.xyz"), TrajectoryError);
}

namespace {

/// Three frames of the default rods, as a run writes them, and where the third begins.
std::pair<std::string, std::size_t> threeFrames() {
    const Scene scene = defaultScene();
    const auto sys = buildInitialState<LinearRotor>(scene, rodPotential(scene));
    std::string text;
    std::size_t third = 0;
    for (double t : {0.1, 0.2, 0.3}) {
        third = text.size();
        text += formatXyzFrame(makeSnapshot(sys, t), TrajectoryLayout::Rod);
    }
    return {text, third};
}

} // namespace

// A run killed while writing a frame leaves it cut short anywhere: in a body line, at a line's
// end, right after the header. Each is dropped with a message, the whole frames before it kept.
TEST(Xyz, ALastFrameCutShortIsDroppedWhenAskedFor) {
    const auto [whole, third] = threeFrames();
    const auto path = tempFile("cut.xyz");
    for (const std::size_t cut :
         {third + 4, third + 30, third + 5000, whole.size() - 1, whole.size() - 10}) {
        std::ofstream(path) << whole.substr(0, cut);
        std::string partial;
        const auto frames = readTrajectory(path.string(), &partial);
        EXPECT_EQ(frames.size(), 2u) << "cut at " << cut;
        EXPECT_NE(partial.find("the last frame is cut short"), std::string::npos) << partial;
        EXPECT_THROW(readTrajectory(path.string()), TrajectoryError) << "cut at " << cut;
    }
    std::ofstream(path) << whole;
    std::string partial = "stale";
    EXPECT_EQ(readTrajectory(path.string(), &partial).size(), 3u);
    EXPECT_TRUE(partial.empty());
}

// Only the last frame may be cut: a broken frame followed by more lines is still an error.
TEST(Xyz, ABrokenFrameInsideTheFileIsStillAnError) {
    std::string text = threeFrames().first;
    const std::size_t line = text.find("\nX ", 1000);
    text.replace(line + 1, 1, "X x"); // a body line of the first frame no longer parses
    const auto path = tempFile("broken.xyz");
    std::ofstream(path) << text;
    std::string partial;
    EXPECT_THROW(readTrajectory(path.string(), &partial), TrajectoryError);
}

} // namespace test_xyz
