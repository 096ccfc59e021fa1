#include "core/xyz.hpp"
#include "core/units.hpp"
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <stdexcept>

namespace terrace {

namespace {

struct PartialFrame {}; // thrown inside readTrajectory only, to drop a cut-off last frame

constexpr TrajectoryLayout layouts[] = {TrajectoryLayout::Sphere, TrajectoryLayout::Rod,
                                        TrajectoryLayout::Top};

/// The columns of a layout before the body column, as files before it had them (species S, R, T).
const char* legacyColumns(TrajectoryLayout layout) {
    switch (layout) {
    case TrajectoryLayout::Sphere:
        return "species:S:1:pos:R:3:velo:R:3";
    case TrajectoryLayout::Rod:
        return "species:S:1:pos:R:3:velo:R:3:axis:R:3:omega:R:3";
    case TrajectoryLayout::Top:
        return "species:S:1:pos:R:3:velo:R:3:orientation:R:4:omega:R:3";
    }
    return "";
}

/// The columns written: a mixture's bodies (Snapshot::species filled) carry their species'
/// index as a last column.
std::string columns(TrajectoryLayout layout, bool speciesColumn = false) {
    return std::string(legacyColumns(layout)) + ":body:I:1" +
           (speciesColumn ? ":species_index:I:1" : "");
}

/// The body column's value: the rotational degrees of freedom, which name the kind.
int bodyCode(TrajectoryLayout layout) {
    return layout == TrajectoryLayout::Sphere ? 0 : (layout == TrajectoryLayout::Rod ? 2 : 3);
}

void put(std::ostream& out, const Vec3& v) {
    out << ' ' << v.x() << ' ' << v.y() << ' ' << v.z();
}

/// The value of key=value or key="value" in an extended XYZ comment line ("" if absent).
std::string field(const std::string& line, const std::string& key) {
    std::size_t pos = 0;
    while ((pos = line.find(key + "=", pos)) != std::string::npos) {
        if (pos == 0 || line[pos - 1] == ' ') break;
        pos += key.size();
    }
    if (pos == std::string::npos) return "";
    pos += key.size() + 1;
    if (pos < line.size() && line[pos] == '"') {
        const auto end = line.find('"', pos + 1);
        return line.substr(pos + 1, end - pos - 1);
    }
    const auto end = line.find(' ', pos);
    return line.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
}

} // namespace

namespace {

/// A frame's time in fs to 15 significant digits: the sample grid's times are decimal numbers
/// (k · run.sample_fs), and their binary round-off (180.00000000000003) is not part of them.
std::string timeText(double fs) {
    char b[32];
    std::snprintf(b, sizeof b, "%.15g", fs);
    return b;
}

void writeXyzHeader(std::ostream& out, int bodies, double time, double L, TrajectoryLayout layout,
                    bool speciesColumn) {
    out << bodies << '\n';
    out << "Lattice=\"" << L << " 0 0 0 " << L << " 0 0 0 " << L
        << "\" Properties=" << columns(layout, speciesColumn)
        << " Time=" << timeText(units::toFs(time))
        << " pbc=\"T T T\" units=\"pos:A velo:A/ps omega:rad/ps Time:fs\"\n";
}

/// The lines of bodies [begin, end).
void writeXyzBodies(std::ostream& out, const Snapshot& f, TrajectoryLayout layout, int begin,
                    int end) {
    const double perPs = 1.0 / units::psPerTimeUnit; // time units -> ps
    for (int i = begin; i < end; ++i) {
        out << 'X'; // ASE's dummy element (readers take species for elements); kind: body
        put(out, f.position[i]);
        put(out, f.velocity[i] * perPs);
        if (layout == TrajectoryLayout::Rod) put(out, f.axis[i]);
        if (layout == TrajectoryLayout::Top) {
            const Quat& q = f.orientation[i];
            out << ' ' << q.w() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z();
        }
        if (layout != TrajectoryLayout::Sphere) put(out, f.omega[i] * perPs);
        out << ' ' << bodyCode(layout);
        if (!f.species.empty()) out << ' ' << f.species[i];
        out << '\n';
    }
}

} // namespace

void writeXyzFrame(std::ostream& out, const Snapshot& f, TrajectoryLayout layout) {
    const auto precision = out.precision(17);
    writeXyzHeader(out, f.size(), f.time, f.boxLength, layout, !f.species.empty());
    writeXyzBodies(out, f, layout, 0, f.size());
    out.precision(precision);
}

void writeXyzFramePieces(int bodies, double time, double boxLength, TrajectoryLayout layout,
                         const std::function<Snapshot(int, int)>& bodiesOf,
                         const std::function<void(std::string_view)>& sink, int bodiesPerPiece) {
    if (bodiesPerPiece < 1) throw std::invalid_argument("writeXyzFramePieces: no bodies per piece");
    std::ostringstream out;
    out.precision(17);
    // The first piece says whether the bodies carry species, which the header names.
    Snapshot piece = bodiesOf(0, std::min(bodies, bodiesPerPiece));
    writeXyzHeader(out, bodies, time, boxLength, layout, !piece.species.empty());
    sink(out.view());
    for (int begin = 0; begin < bodies; begin += bodiesPerPiece) {
        const int end = std::min(bodies, begin + bodiesPerPiece);
        if (begin > 0) piece = bodiesOf(begin, end);
        if (piece.size() != end - begin)
            throw std::logic_error("writeXyzFramePieces: a piece of the wrong size");
        out.str(std::string());
        writeXyzBodies(out, piece, layout, 0, piece.size());
        sink(out.view());
    }
}

std::string formatXyzFrame(const Snapshot& frame, TrajectoryLayout layout) {
    std::ostringstream out;
    writeXyzFrame(out, frame, layout);
    return std::move(out).str();
}

long forEachTrajectoryFrame(const std::string& path, const std::function<void(Snapshot&&)>& each,
                            std::string* partialLastFrame) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw TrajectoryError(path + ": is a directory, not a trajectory");
    std::ifstream in(path);
    if (!in) throw TrajectoryError(path + ": cannot open the trajectory: " + std::strerror(errno));
    long frames = 0; // whole frames handed on
    std::string line;
    long lineNo = 0;
    long frameLine = 0; // where the frame being read starts
    if (partialLastFrame) partialLastFrame->clear();
    // A frame is cut short when the file ends inside it: a line missing, or its last line
    // without the newline every written line ends with. Anything else malformed is an error.
    auto fail = [&](const std::string& what, bool cutShort) {
        if (partialLastFrame && cutShort) {
            *partialLastFrame = path + ":" + std::to_string(frameLine) +
                                ": the last frame is cut short (" + what + "); read the " +
                                std::to_string(frames) + " whole frames before it";
            throw PartialFrame{};
        }
        throw TrajectoryError(path + ":" + std::to_string(lineNo) + ": " + what);
    };
    // getline sets eof when the file ended before a newline: the line read was cut.
    auto next = [&](const char* missing) {
        if (!std::getline(in, line)) fail(missing, true);
        ++lineNo;
        return !in.eof();
    };
    const double perPs = 1.0 / units::psPerTimeUnit; // divide: ps^-1 -> per time unit
    try {
        while (std::getline(in, line)) {
            ++lineNo;
            frameLine = lineNo;
            if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
            const bool countWhole = !in.eof();
            long n = 0;
            try {
                std::size_t used = 0;
                n = std::stol(line, &used);
                if (line.find_first_not_of(" \t\r", used) != std::string::npos) throw 0;
            } catch (...) {
                fail("expected the number of bodies", !countWhole);
            }
            if (n < 0) fail("negative number of bodies", false);
            const bool headerWhole = next("missing comment line");
            Snapshot f;
            std::istringstream lattice(field(line, "Lattice"));
            double a[9];
            for (double& x : a)
                if (!(lattice >> x)) fail("missing or malformed Lattice=", !headerWhole);
            f.boxLength = a[0];
            const std::string time = field(line, "Time");
            if (time.empty()) fail("missing Time=", !headerWhole);
            try {
                f.time = units::fromFs(std::stod(time));
            } catch (const std::logic_error&) {
                fail("malformed Time=" + time, !headerWhole);
            }
            // Files written before the body column (species S, R, T) are read as well.
            const std::string props = field(line, "Properties");
            TrajectoryLayout layout = TrajectoryLayout::Sphere;
            bool known = false, bodyColumn = false, speciesColumn = false;
            for (const TrajectoryLayout l : layouts)
                if (props == columns(l) || props == columns(l, true) || props == legacyColumns(l)) {
                    layout = l;
                    known = true;
                    bodyColumn = props != legacyColumns(l);
                    speciesColumn = props == columns(l, true);
                }
            if (!known) fail("unsupported Properties=" + props, !headerWhole);
            for (long i = 0; i < n; ++i) {
                const bool whole = next("frame ends early");
                std::istringstream row(line);
                std::string element; // X, or S, R, T in old files: the kind is the layout
                Vec3 r, v, s = Vec3::UnitZ(), w = Vec3::Zero();
                row >> element >> r.x() >> r.y() >> r.z() >> v.x() >> v.y() >> v.z();
                if (layout == TrajectoryLayout::Rod) row >> s.x() >> s.y() >> s.z();
                if (layout == TrajectoryLayout::Top) {
                    double qw, qx, qy, qz;
                    row >> qw >> qx >> qy >> qz;
                    const Quat q(qw, qx, qy, qz);
                    f.orientation.push_back(q);
                    s = q * Vec3::UnitZ();
                }
                if (layout != TrajectoryLayout::Sphere) row >> w.x() >> w.y() >> w.z();
                int body = bodyCode(layout);
                if (bodyColumn) row >> body;
                std::int32_t speciesIndex = 0;
                if (speciesColumn) row >> speciesIndex;
                if (!row || body != bodyCode(layout) || speciesIndex < 0)
                    fail("malformed body line", !whole);
                if (!whole) fail("the body line has no end", true);
                f.position.push_back(r);
                f.velocity.push_back(v / perPs);
                f.axis.push_back(s);
                f.omega.push_back(w / perPs);
                if (speciesColumn) f.species.push_back(speciesIndex);
            }
            ++frames;
            each(std::move(f));
        }
    } catch (const PartialFrame&) {
    }
    return frames;
}

std::vector<Snapshot> readTrajectory(const std::string& path, std::string* partialLastFrame) {
    std::vector<Snapshot> frames;
    forEachTrajectoryFrame(
        path, [&frames](Snapshot&& f) { frames.push_back(std::move(f)); }, partialLastFrame);
    return frames;
}

} // namespace terrace
