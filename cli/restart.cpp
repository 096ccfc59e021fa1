#include "cli/restart.hpp"
#include "core/output_file.hpp"
#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace terrace::cli {

namespace {

/// A record's numbers in the order they are stored.
template <class R, class F> void forEachNumber(R& e, F&& f) {
    f(e.time), f(e.tPs), f(e.total), f(e.potential), f(e.kinetic), f(e.kineticTranslational);
    f(e.virial), f(e.collisions), f(e.continuousPotential), f(e.continuousVirial), f(e.bath);
}

constexpr std::size_t recordBytes = 11 * sizeof(double);

} // namespace

nlohmann::json recordsToBinary(const std::vector<SampleRecord>& records) {
    std::vector<std::uint8_t> bytes;
    bytes.reserve(records.size() * recordBytes);
    for (const SampleRecord& e : records)
        forEachNumber(e, [&](const double& x) {
            const auto* p = reinterpret_cast<const std::uint8_t*>(&x);
            bytes.insert(bytes.end(), p, p + sizeof x);
        });
    return nlohmann::json::binary(std::move(bytes));
}

std::vector<SampleRecord> recordsFromBinary(const nlohmann::json& j) {
    const auto& bytes = j.get_binary();
    if (bytes.size() % recordBytes != 0)
        throw std::runtime_error("restart: the sample records are not whole records");
    std::vector<SampleRecord> records(bytes.size() / recordBytes);
    const std::uint8_t* p = bytes.data();
    for (SampleRecord& e : records)
        forEachNumber(e, [&](double& x) {
            std::memcpy(&x, p, sizeof x);
            p += sizeof x;
        });
    return records;
}

namespace {

constexpr std::size_t trailerSize = 16; // the document's length, then the CRC-64 of all before

std::array<std::uint64_t, 256> crcTable() {
    std::array<std::uint64_t, 256> table{};
    for (std::uint64_t b = 0; b < 256; ++b) {
        std::uint64_t c = b;
        for (int k = 0; k < 8; ++k)
            c = (c >> 1) ^ ((c & 1) ? 0xC96C5795D7870F42ull : 0);
        table[b] = c;
    }
    return table;
}

void putLittleEndian(std::string& out, std::uint64_t x) {
    for (int k = 0; k < 8; ++k)
        out.push_back(char((x >> (8 * k)) & 0xff));
}

std::uint64_t getLittleEndian(std::string_view bytes, std::size_t at) {
    std::uint64_t x = 0;
    for (int k = 0; k < 8; ++k)
        x |= std::uint64_t(static_cast<unsigned char>(bytes[at + k])) << (8 * k);
    return x;
}

std::string hex(std::uint64_t x) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(x));
    return text;
}

} // namespace

std::uint64_t crc64(std::string_view bytes, std::uint64_t crc) {
    static const std::array<std::uint64_t, 256> table = crcTable();
    crc = ~crc;
    for (const char c : bytes)
        crc = table[(crc ^ static_cast<unsigned char>(c)) & 0xff] ^ (crc >> 8);
    return ~crc;
}

std::uint64_t tailChecksum(const std::filesystem::path& path, std::int64_t length) {
    const std::int64_t from = std::max<std::int64_t>(0, length - tailBytes);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(path.string() + ": cannot open: " + std::strerror(errno));
    std::string bytes(std::size_t(length - from), '\0');
    in.seekg(from);
    in.read(bytes.data(), std::streamsize(bytes.size()));
    if (in.gcount() != std::streamsize(bytes.size()))
        throw IoError(path.string() + ": holds fewer than the " + std::to_string(length) +
                      " bytes of its restart point");
    return crc64(bytes);
}

void writeRestart(const std::filesystem::path& dir, const nlohmann::json& restart) {
    const std::vector<std::uint8_t> cbor = nlohmann::json::to_cbor(restart);
    std::string bytes(reinterpret_cast<const char*>(cbor.data()), cbor.size());
    putLittleEndian(bytes, cbor.size());
    putLittleEndian(bytes, crc64(bytes));
    writeFileAtomically(dir / "restart.bin", bytes);
}

IoError damagedRestart(const std::filesystem::path& dir, const nlohmann::json::exception& e) {
    const std::string text = e.what();
    const auto tag = text.find("] "); // nlohmann's "[json.exception.…] " prefix
    return IoError((dir / "restart.bin").string() +
                   ": damaged, or written by another version of terrace (" +
                   (tag == std::string::npos ? text : text.substr(tag + 2)) + ")");
}

nlohmann::json decodeRestart(const std::string& bytes, const std::filesystem::path& path) {
    const std::size_t size = bytes.size();
    // Versions before 5 wrote the document alone: read whole, to name their version.
    const bool framed = size >= trailerSize && getLittleEndian(bytes, size - trailerSize) ==
                                                   std::uint64_t(size - trailerSize);
    if (framed) {
        const std::uint64_t stored = getLittleEndian(bytes, size - 8);
        const std::uint64_t actual = crc64(std::string_view(bytes).substr(0, size - 8));
        if (stored != actual)
            throw IoError(path.string() + ": damaged: its checksum (CRC-64 " + hex(actual) +
                          ") is not the one it was written with (" + hex(stored) +
                          "): continue from a good copy, or start the run again");
    }
    nlohmann::json j;
    try {
        j = nlohmann::json::from_cbor(framed ? std::string_view(bytes).substr(0, size - trailerSize)
                                             : std::string_view(bytes),
                                      true, false);
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
    if (!framed || j.is_discarded() || !j.is_object() || format != restartFormat)
        throw IoError(path.string() + ": not a terrace restart file (or a damaged one)");
    return j;
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
    return decodeRestart(readWholeFile(path), path);
}

nlohmann::json runIdentity(std::uint64_t sceneChecksum, int bodies, const std::string& engine) {
    return {{"scene_crc64", sceneChecksum}, {"n_bodies", bodies}, {"engine", engine}};
}

void checkRunIdentity(const std::filesystem::path& dir, const nlohmann::json& restart) {
    const auto restartPath = (dir / "restart.bin").string();
    const auto scenePath = dir / "scene.json";
    try {
        const auto& identity = restart.at("identity");
        const auto& scene = restart.at("scene");
        if (identity.at("n_bodies") != restart.at("n_bodies") ||
            identity.at("engine") != scene.at("engine"))
            throw IoError(restartPath + ": damaged: its identity (N " +
                          identity.at("n_bodies").dump() + ", engine " +
                          identity.at("engine").dump() + ") is not that of its own run");
        std::error_code ec;
        if (!std::filesystem::exists(scenePath, ec))
            throw IoError(scenePath.string() +
                          ": missing: restart.bin cannot be checked against this run's scene");
        const std::string text = readWholeFile(scenePath);
        const std::uint64_t recorded = identity.at("scene_crc64").get<std::uint64_t>();
        const std::uint64_t actual = crc64(text);
        if (recorded == actual) return;
        // Named by the settings that differ (the first three), when both read as JSON.
        std::string what;
        const nlohmann::json here = nlohmann::json::parse(text, nullptr, false);
        if (!here.is_discarded()) {
            std::vector<std::string> keys;
            for (const auto& op : nlohmann::json::diff(here, scene)) {
                std::string key = op.value("path", "");
                std::replace(key.begin(), key.end(), '/', '.');
                if (!key.empty() && key.front() == '.') key.erase(0, 1);
                if (!key.empty()) keys.push_back(key);
            }
            for (std::size_t k = 0; k < std::min<std::size_t>(keys.size(), 3); ++k)
                what += (k == 0 ? "; " : ", ") + keys[k];
            if (keys.size() > 3) what += ", …";
            if (!keys.empty()) what += keys.size() == 1 ? " differs" : " differ";
        }
        throw IoError(restartPath + ": from another run: the scene it was written for (CRC-64 " +
                      hex(recorded) + ") is not " + scenePath.string() + " (" + hex(actual) + what +
                      ")");
    } catch (const nlohmann::json::exception& e) {
        throw damagedRestart(dir, e);
    }
}

} // namespace terrace::cli
