#include "cli/restart.hpp"
#include "core/output_file.hpp"
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>

namespace terrace::cli {

namespace {

void put(std::string& out, double x) {
    char b[sizeof x];
    std::memcpy(b, &x, sizeof x);
    out.append(b, sizeof x);
}

void put(std::string& out, const Vec3& v) {
    put(out, v.x()), put(out, v.y()), put(out, v.z());
}

std::size_t recordDoubles(int bodies, bool withOrientation) {
    return 10 + std::size_t(bodies) * (withOrientation ? 16 : 12);
}

std::string sampleHead(double time, const SampleRecord& e) {
    std::string out;
    put(out, time), put(out, e.tPs), put(out, e.total), put(out, e.potential);
    put(out, e.kinetic), put(out, e.kineticTranslational), put(out, e.virial);
    put(out, e.collisions), put(out, e.continuousPotential), put(out, e.continuousVirial);
    return out;
}

void putBodies(std::string& out, const Snapshot& s) {
    const bool tops = !s.orientation.empty();
    for (int i = 0; i < s.size(); ++i) {
        put(out, s.position[i]), put(out, s.velocity[i]), put(out, s.axis[i]);
        put(out, s.omega[i]);
        if (tops) {
            const Quat& q = s.orientation[i];
            put(out, q.w()), put(out, q.x()), put(out, q.y()), put(out, q.z());
        }
    }
}

} // namespace

std::string encodeSample(const Snapshot& s, const SampleRecord& e) {
    std::string out = sampleHead(s.time, e);
    out.reserve(recordDoubles(s.size(), !s.orientation.empty()) * sizeof(double));
    putBodies(out, s);
    return out;
}

void writeSamplePieces(int bodies, double time, const SampleRecord& e,
                       const std::function<Snapshot(int, int)>& bodiesOf, const PieceSink& sink,
                       int bodiesPerPiece) {
    sink(sampleHead(time, e));
    std::string out;
    for (int begin = 0; begin < bodies; begin += bodiesPerPiece) {
        out.clear();
        putBodies(out, bodiesOf(begin, std::min(bodies, begin + bodiesPerPiece)));
        sink(out);
    }
}

void decodeSamples(const std::string& bytes, int bodies, bool withOrientation, double boxLength,
                   std::vector<Snapshot>& samples, std::vector<SampleRecord>& energies) {
    const std::size_t record = recordDoubles(bodies, withOrientation) * sizeof(double);
    if (bytes.size() % record != 0)
        throw std::runtime_error("samples.bin does not hold whole sample records");
    const char* p = bytes.data();
    auto get = [&p] {
        double x;
        std::memcpy(&x, p, sizeof x);
        p += sizeof x;
        return x;
    };
    auto vec = [&] {
        const double x = get(), y = get(), z = get();
        return Vec3(x, y, z);
    };
    for (std::size_t k = 0; k < bytes.size() / record; ++k) {
        Snapshot s;
        s.boxLength = boxLength;
        s.time = get();
        SampleRecord e;
        e.time = s.time;
        e.tPs = get(), e.total = get(), e.potential = get(), e.kinetic = get();
        e.kineticTranslational = get(), e.virial = get(), e.collisions = get();
        e.continuousPotential = get(), e.continuousVirial = get();
        for (int i = 0; i < bodies; ++i) {
            s.position.push_back(vec());
            s.velocity.push_back(vec());
            s.axis.push_back(vec());
            s.omega.push_back(vec());
            if (withOrientation) {
                const double w = get(), x = get(), y = get(), z = get();
                s.orientation.emplace_back(w, x, y, z);
            }
        }
        samples.push_back(std::move(s));
        energies.push_back(e);
    }
}

long forEachSample(const std::filesystem::path& path, int bodies, bool withOrientation,
                   double boxLength,
                   const std::function<void(const Snapshot&, const SampleRecord&)>& each) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(path.string() + ": cannot open: " + std::strerror(errno));
    const std::size_t record = recordDoubles(bodies, withOrientation) * sizeof(double);
    std::string bytes(record, '\0');
    long count = 0;
    std::vector<Snapshot> one;
    std::vector<SampleRecord> energy;
    while (true) {
        in.read(bytes.data(), std::streamsize(record));
        const std::size_t got = static_cast<std::size_t>(in.gcount());
        if (got == 0) break;
        if (got != record)
            throw std::runtime_error("samples.bin does not hold whole sample records");
        one.clear(), energy.clear();
        decodeSamples(bytes, bodies, withOrientation, boxLength, one, energy);
        each(one.front(), energy.front());
        ++count;
    }
    if (in.bad()) throw IoError(path.string() + ": read failed: " + std::strerror(errno));
    return count;
}

void writeRestart(const std::filesystem::path& dir, const nlohmann::json& restart) {
    const std::vector<std::uint8_t> bytes = nlohmann::json::to_cbor(restart);
    writeFileAtomically(
        dir / "restart.bin",
        std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

IoError damagedRestart(const std::filesystem::path& dir, const nlohmann::json::exception& e) {
    const std::string text = e.what();
    const auto tag = text.find("] "); // nlohmann's "[json.exception.…] " prefix
    return IoError((dir / "restart.bin").string() +
                   ": damaged, or written by another version of terrace (" +
                   (tag == std::string::npos ? text : text.substr(tag + 2)) + ")");
}

nlohmann::json readRestart(const std::filesystem::path& dir) {
    const auto path = dir / "restart.bin";
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
        const bool finished = std::filesystem::exists(dir / "summary.json", ec);
        const bool started = std::filesystem::exists(dir / "scene.json", ec);
        throw IoError(
            dir.string() + ": no restart file (restart.bin): " +
            (finished  ? "the run finished, or was not started with output.restart_every_ps > 0"
             : started ? "the run stopped before its first restart point, or was not started "
                         "with output.restart_every_ps > 0: start it again"
                       : "no terrace run was started in this directory"));
    }
    const std::string bytes = readWholeFile(path);
    nlohmann::json j;
    try {
        j = nlohmann::json::from_cbor(bytes, true, false);
    } catch (const nlohmann::json::exception&) {
        // Even without exceptions the parser throws on a size no container can take.
        j = nlohmann::json(nlohmann::json::value_t::discarded);
    }
    const auto format = j.is_object() && j.contains("format") && j["format"].is_string()
                            ? j["format"].get<std::string>()
                            : std::string();
    if (format != restartFormat && format.rfind("terrace restart ", 0) == 0)
        throw IoError(path.string() + ": written by another version of terrace ('" + format +
                      "'; this one reads '" + restartFormat + "'): start the run again");
    if (j.is_discarded() || !j.is_object() || format != restartFormat)
        throw IoError(path.string() + ": not a terrace restart file (or a damaged one)");
    return j;
}

} // namespace terrace::cli
