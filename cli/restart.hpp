#pragma once
// Restart files: everything a run needs to go on from a point of its time grid as if it had never
// stopped (DESIGN.md "Output a user can trust").
//
//   DIR/restart.bin   one CBOR document (RFC 8949; nlohmann::json::to_cbor) and a 16-byte trailer
//                     (the document's length, then the CRC-64/XZ of all bytes before it, both
//                     64-bit little-endian), written atomically at every output.restart_every_ps
//                     and when a signal stops the run. The trailer is checked before anything of
//                     the file is read: any damage confined to 64 bits, and all but 2⁻⁶⁴ of the
//                     rest, is refused. The document holds:
//                       format, scene (resolved), the run's identity (the CRC-64 of DIR/scene.json
//                       as the run wrote it, N, the engine), phase (equilibration | production),
//                       the number of thermostat ticks or samples done, the bodies (every number of
//                       their states as raw bytes: exact, and compact; a mixture's species among
//                       them, as a 32-bit integer), the engine's checkpoint
//                       (DMD: clock, pair terraces as raw bytes, horizon stream; SMD: step count;
//                       both: the heat bath's stream, energy and clock when run.heat_bath is set),
//                       the run's accumulators (production start, initial momentum, production
//                       statistics, CPU seconds), the lengths of trajectory.xyz and thermo.csv at
//                       that point with the checksums of their tails, and, in production:
//                         analysis  the streaming analysis' accumulators as raw bytes
//                                   (analysis/state_bytes.hpp: g(r)'s histograms and the
//                                   terracing profile, the correlators' rings, kept transforms,
//                                   spectra and sums, the block counts): their size is fixed by
//                                   the settings, the followed bodies and g(r)'s bins, whatever
//                                   the run's length;
//                         sample_statistics  what summary.json reports of the samples, as
//                                   raw bytes (cli/sample_statistics.hpp: energy moments and
//                                   drift sums, block sums over the planned samples, the last
//                                   sample), about a kilobyte;
//                         thermo_row the sample of thermo.csv's last row (one SampleRecord).
//
// The run's history (its samples) is not kept: a continued run cuts trajectory.xyz and
// thermo.csv back to their lengths in the restart file, takes the analysis' state and the sample
// statistics back, rebuilds the engine from the bodies and the checkpoint, and goes on; nothing
// is replayed, and the file is as large after 10 samples as after 10⁶ (but for the integers that
// count them), so continuing costs the same too.
// At every restart point the running engine is rebuilt the same way, so that a run continued from
// a restart file undergoes the same events and writes the same bytes as one that never stopped.
#include "core/huge_pages.hpp"
#include "core/output_file.hpp"
#include "core/snapshot.hpp"
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace terrace::cli {

/// Version 2: samples.bin records carry K_trans, W and the collision count, and restart.bin the
/// length of thermo.csv. Version 3: the DMD checkpoint's pair terraces are raw bytes
/// (dmd/engine_start.hpp). Version 5: the checksum trailer and the run's identity. Version 6: the
/// analysis' state and the samples' records in restart.bin, no samples.bin. Version 7: the sample
/// statistics' state and thermo.csv's last row in place of the samples' records. Version 8: the
/// samples carry the heat bath's energy, and the engines' checkpoints its state. Files of another
/// version are refused, naming both versions.
inline constexpr const char* restartFormat = "terrace restart 8";

/// CRC-64/XZ (ECMA-182 polynomial, reflected, all ones in and out) of `bytes`, continuing from
/// `crc` (the value returned for the bytes before them; 0 to start).
std::uint64_t crc64(std::string_view bytes, std::uint64_t crc = 0);

/// How much of each growing file's end before its restart point restart.bin checksums.
inline constexpr std::int64_t tailBytes = 64 * 1024;
/// CRC-64 of the last min(length, tailBytes) bytes before `length` in the file at `path`; throws
/// IoError when the file cannot be read or is shorter than `length`.
std::uint64_t tailChecksum(const std::filesystem::path& path, std::int64_t length);

/// One production sample and its energies (kJ/mol), as the run loop keeps them.
struct SampleRecord {
    double tPs = 0.0, total = 0.0, potential = 0.0, kinetic = 0.0;
    double kineticTranslational = 0.0; // ½ m Σ v²: the kinetic term of the pressure
    double virial = 0.0;     // SMD: Σ r_ij·F_ij at the sample; DMD: the running Σ r_ij·Δp_i
    double collisions = 0.0; // DMD: collisions since production began (exact below 2⁵³); SMD: 0
    double time = 0.0;       // engine time units (the snapshot's time)
    // The continuous model's U and W on the sample's configuration (core/continuous_sums.hpp),
    // kJ/mol, taken on g(r) frames; NaN on the other samples.
    double continuousPotential = std::numeric_limits<double>::quiet_NaN();
    double continuousVirial = std::numeric_limits<double>::quiet_NaN();
    // Kinetic energy the heat bath has taken out since the run began (0 without one): total + bath
    // is the conserved effective energy of a thermostatted run.
    double bath = 0.0;
};

/// Records as raw bytes (11 doubles each, in SampleRecord's order): exact, and compact in CBOR.
nlohmann::json recordsToBinary(const std::vector<SampleRecord>& records);
/// The records of recordsToBinary; std::runtime_error when the bytes are not whole records.
std::vector<SampleRecord> recordsFromBinary(const nlohmann::json& j);

void writeRestart(const std::filesystem::path& dir, const nlohmann::json& restart);
/// "DIR/restart.bin: damaged, or written by another version of terrace (<what is missing>)" for
/// a restart file whose content does not read (a key missing, a value of the wrong type).
IoError damagedRestart(const std::filesystem::path& dir, const nlohmann::json::exception& e);

/// Reads DIR/restart.bin; IoError when absent, unreadable or damaged (its checksum), naming what
/// to do.
nlohmann::json readRestart(const std::filesystem::path& dir);
/// The restart document in the bytes of a restart file at `path` (named in the errors).
nlohmann::json decodeRestart(const std::string& bytes, const std::filesystem::path& path);

/// The identity a restart file records: the CRC-64 of DIR/scene.json's bytes, N, the engine.
nlohmann::json runIdentity(std::uint64_t sceneChecksum, int bodies, const std::string& engine);
/// Refuses a restart file that belongs to another run than the one in `dir`: its identity must
/// name DIR/scene.json's checksum, and its N and engine those of its scene.
void checkRunIdentity(const std::filesystem::path& dir, const nlohmann::json& restart);

/// Calls f on every vector and matrix of a body's state (all kinds: r, v; s, w; A, L), and on a
/// mixture's species as a one-element span: each has size() and data().
template <class State, class F> void forEachField(State& b, F&& f) {
    f(b.r), f(b.v);
    if constexpr (requires { b.s; }) f(b.s);
    if constexpr (requires { b.w; }) f(b.w);
    if constexpr (requires { b.A; }) f(b.A);
    if constexpr (requires { b.L; }) f(b.L);
    if constexpr (requires { b.species; }) f(std::span(&b.species, std::size_t{1}));
}

/// Every number of every body's state, in order, as raw bytes: exact, and compact in CBOR.
template <class State, class A> nlohmann::json bodiesToBinary(const std::vector<State, A>& bodies) {
    std::vector<std::uint8_t> bytes;
    std::size_t perBody = 0; // reserved whole: grown, it could hold twice the bytes
    const State probe{};
    forEachField(probe, [&](const auto& m) { perBody += m.size() * sizeof(*m.data()); });
    bytes.reserve(bodies.size() * perBody);
    for (const auto& b : bodies)
        forEachField(b, [&](const auto& m) {
            const auto* p = reinterpret_cast<const std::uint8_t*>(m.data());
            bytes.insert(bytes.end(), p, p + m.size() * sizeof(*m.data()));
        });
    return nlohmann::json::binary(std::move(bytes));
}

template <class State> BodyArray<State> bodiesFromBinary(const nlohmann::json& j, int n) {
    const auto& bytes = j.get_binary();
    BodyArray<State> bodies(n);
    std::size_t at = 0;
    for (auto& b : bodies)
        forEachField(b, [&](auto&& m) {
            const std::size_t size = m.size() * sizeof(*m.data());
            if (at + size > bytes.size())
                throw std::runtime_error("restart: too few body records for " + std::to_string(n) +
                                         " bodies of this kind");
            std::memcpy(m.data(), bytes.data() + at, size);
            at += size;
        });
    if (at != bytes.size())
        throw std::runtime_error("restart: more body records than " + std::to_string(n) +
                                 " bodies of this kind");
    return bodies;
}

/// Refuses a mixture's body whose species (read back from a restart file) is not one of the
/// scene's `species`: the engines index their tables by it.
template <class Bodies> void checkSpecies(const Bodies& bodies, int species) {
    for (std::size_t i = 0; i < bodies.size(); ++i)
        if (bodies[i].species < 0 || bodies[i].species >= species)
            throw std::runtime_error("restart: body " + std::to_string(i) + " has species " +
                                     std::to_string(bodies[i].species) + ", where the scene has " +
                                     std::to_string(species));
}

} // namespace terrace::cli
