#include "cli/resource_check.hpp"
#include "cli/dispatch.hpp"
#include "cli/run_record.hpp"
#include "core/free_orbit.hpp"
#include "dmd/agendas.hpp"
#include "dmd/neighbour_lists.hpp"
#include "dmd/settings.hpp"
#include "smd/parameters.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sys/resource.h>
#include <sys/statvfs.h>
#include <unistd.h>

namespace terrace::cli {

namespace {

/// The process before any body: code, libraries, the allocator's arenas, the scene (measured:
/// 12 MB of peak RSS at N = 512, where the bodies take under 1 MB).
constexpr double processBytes = 12.0 * (1 << 20);

/// A body of a sample's snapshot (position, velocity, axis, ω; a top's quaternion too), which the
/// analysis and the outputs read beside the engine.
double snapshotBytesPerBody(int rotationalDof) {
    return 4.0 * sizeof(Vec3) + (rotationalDof == 3 ? 4.0 * sizeof(double) : 0.0);
}

/// Bodies expected within `reach` (Å) of a body at number density rho (Å⁻³).
double withinReach(double rho, double reach) {
    return rho * 4.0 / 3.0 * std::numbers::pi * reach * reach * reach;
}

// The DMD engine's parts per body (dmd/engine.hpp memoryByPart), by the sizes its headers fix:
// a body's book is one cache line (dmd/schedule.hpp BodyBook), its agenda block four
// (dmd/agendas.hpp Block, 15 events of 16 B); the calendar (the tournament tree,
// dmd/tournament_queue.hpp) holds one entry per body: a leaf (a 32-B event, its sequence and
// generation) and two 16-B nodes, plus the body's handle; the cell list five ints and a code.
constexpr double bookBytes = 64.0, agendaBlockBytes = 256.0;
constexpr double calendarBytes = 48.0 + 2.0 * 16.0 + 8.0;
constexpr double cellBytes = 5.0 * sizeof(int) + sizeof(std::uint64_t);
/// Index arrays (the cell order's two numberings, the relist's stamps and scan) and the spills:
/// the agendas that outgrow their 15 slots and the lists their records, from the pools
/// (docs/PERFORMANCE.md: 87-216 B a body of spills in a dense liquid at 32 768 rods).
constexpr double dmdOtherBytes = 4.0 * sizeof(int) + 160.0;

/// A DMD engine of n bodies at the scene's density, its lists reaching r_m + skin.
template <BodyKind K> double dmdEngineBytes(int n, double rho, double boxLength, double rm) {
    const double skin = dmd::listSkin(rm, rho, boxLength);
    const int capacity = dmd::listCapacity(rm + skin, rho, n);
    // A list's record: its size and spill, then the partners and their terraces (4 B each), and
    // its anchor.
    const double listBytes = (2.0 + 2.0 * capacity) * sizeof(std::int32_t) + sizeof(Vec3);
    const double perBody = sizeof(typename K::State) + sizeof(FreeOrbit<K>) + bookBytes +
                           agendaBlockBytes + calendarBytes + cellBytes + listBytes + dmdOtherBytes;
    return double(n) * perBody;
}

/// An SMD engine of n bodies: the bodies, their unwrapped positions, per list slot the local
/// position, the orientation the potential reads, force and torque, the list's order, start,
/// offset and anchor, and the half list of pairs within r_u + skin (4 B a pair, 1/8 reserve).
template <BodyKind K, class Orientation>
double smdEngineBytes(int n, double rho, double reach, bool orientational) {
    const double perBody = sizeof(typename K::State) + 2.0 * sizeof(Vec3) +
                           (orientational ? sizeof(Orientation) : 0.0) + 2.0 * sizeof(Vec3) +
                           sizeof(int) + sizeof(std::size_t) + 2.0 * sizeof(Vec3) +
                           2.0 * sizeof(int) + 1.0;
    const double pairs = 0.5 * std::min(withinReach(rho, reach), double(n - 1));
    return double(n) * (perBody + 1.125 * pairs * sizeof(std::uint32_t));
}

double engineBytes(const Scene& scene) {
    const int n = scene.state.particles.empty() ? scene.state.n : int(scene.state.particles.size());
    const double L = scene.boxLength();
    const double rho = double(n) / (L * L * L);
    return withBodyAndPotential(scene, [&]<class K, class P>(const P& potential) {
        const double snapshot = double(n) * snapshotBytesPerBody(K::rotationalDof);
        if (scene.engine == "smd") {
            const auto model = sceneModel(scene, potential, false);
            using M = std::remove_const_t<decltype(model)>;
            const double reach = model.range() + smd::parameters(scene, L, model.range()).skin;
            return processBytes + snapshot +
                   smdEngineBytes<K, typename M::Orientation>(n, rho, reach, isOrientational<M>);
        }
        const auto model = sceneModel(scene, potential, true);
        const double rm = dmd::readDmdSettings(scene.dmd, model, scene.kT(), L).rm;
        return processBytes + snapshot + dmdEngineBytes<K>(n, rho, L, rm);
    });
}

/// Characters of one number of a trajectory line at 17 significant digits with its separator:
/// "-12.345678901234567" is 19, an exponent ("-1.2345678901234567e-05") 23.
constexpr double xyzNumberBytes = 21.0;

double frameBytes(int n, int rotationalDof) {
    // Species, position, velocity; a rod's axis, a top's quaternion; ω; the body code.
    const int numbers = 6 + (rotationalDof == 2 ? 3 : 0) + (rotationalDof == 3 ? 4 : 0) +
                        (rotationalDof > 0 ? 3 : 0);
    const double header = 256.0;
    return header + double(n) * (2.0 + numbers * xyzNumberBytes + 2.0);
}

int rotationalDofOf(const Scene& scene) {
    return withBodyAndPotential(scene, []<class K, class P>(const P&) { return K::rotationalDof; });
}

double fileSize(const std::filesystem::path& path) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    return ec ? 0.0 : double(size);
}

/// A cgroup file's number of bytes; negative for "max", a missing file or v1's "no limit" (a
/// number near 2^63).
double cgroupNumber(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::string word;
    if (!(in >> word) || word == "max") return -1.0;
    try {
        const double x = std::stod(word);
        return x < 0x1p62 ? x : -1.0;
    } catch (const std::exception&) {
        return -1.0;
    }
}

/// Room under the memory limits of this process's cgroups: limit − usage, the smallest over the
/// process's cgroup and its ancestors (v2: memory.max, memory.current; v1: memory.limit_in_bytes,
/// memory.usage_in_bytes), and over the root of the mount, which a container sees as its own
/// cgroup; negative when none applies.
double cgroupRoom() {
    std::ifstream self("/proc/self/cgroup");
    std::string line, v2, v1;
    while (std::getline(self, line)) {
        if (line.rfind("0::", 0) == 0) v2 = line.substr(3);
        const auto colon = line.find(':');
        if (colon != std::string::npos && line.compare(colon, 8, ":memory:") == 0)
            v1 = line.substr(colon + 8);
    }
    double room = -1.0;
    auto limitAt = [&room](const std::filesystem::path& dir, const char* limitFile,
                           const char* usageFile) {
        const double limit = cgroupNumber(dir / limitFile);
        if (limit < 0.0) return;
        const double left = std::max(0.0, limit - std::max(0.0, cgroupNumber(dir / usageFile)));
        room = room < 0.0 ? left : std::min(room, left);
    };
    auto walk = [&](const std::filesystem::path& root, const std::string& path,
                    const char* limitFile, const char* usageFile) {
        std::filesystem::path p = root / std::filesystem::path(path).relative_path();
        for (; p.string().size() > root.string().size(); p = p.parent_path())
            limitAt(p, limitFile, usageFile);
        limitAt(root, limitFile, usageFile);
    };
    if (!v2.empty()) walk("/sys/fs/cgroup", v2, "memory.max", "memory.current");
    if (!v1.empty())
        walk("/sys/fs/cgroup/memory", v1, "memory.limit_in_bytes", "memory.usage_in_bytes");
    return room;
}

} // namespace

MemoryEstimate memoryEstimate(const Scene& scene) {
    return {engineBytes(scene), analysisBytes(scene)};
}

DiskEstimate diskEstimate(const Scene& scene) {
    const RunPlan plan = planRun(scene);
    const int n = scene.state.particles.empty() ? scene.state.n : int(scene.state.particles.size());
    const int dof = rotationalDofOf(scene);
    DiskEstimate d;
    const double frame = frameBytes(n, dof);
    // A GSD frame: position, image, orientation, velocity, angular momentum, 17 numbers of 4 B
    // a body, and the index's entries (core/gsd_frame.hpp).
    const bool gsd = scene.output.trajectory_format == "gsd";
    if (gsd) d.trajectoryName = "trajectory.gsd";
    const double trajectoryFrame = gsd ? 17.0 * 4.0 * double(n) + 1024.0 : frame;
    if (plan.trajectoryEvery > 0)
        d.trajectory = (std::floor(double(plan.productionSamples) / plan.trajectoryEvery) + 1.0) *
                       trajectoryFrame;
    // A thermo.csv row: a dozen numbers at 17 significant digits.
    if (plan.thermoEvery > 0)
        d.thermo = (std::floor(double(plan.productionSamples) / plan.thermoEvery) + 2.0) * 12.0 *
                   xyzNumberBytes;
    if (plan.restartEvery > 0) {
        // restart.bin: the bodies and the engine's checkpoint (DMD: 12 B a pair off terrace 0,
        // a few per body), about a body's snapshot record and half again, and the analysis'
        // state: its accumulators, what the analysis holds in memory (cli/restart.hpp), and the
        // sample statistics' kilobyte.
        d.restart = 2.0 * (1.5 * double(n) * (dof == 3 ? 16.0 : 12.0) * sizeof(double) +
                           analysisBytes(scene));
    }
    // scene.json and summary.json are small; initial.xyz is a frame; the CSVs hold a row per bin
    // or lag (a few thousand rows of a few numbers).
    d.results = frame + 4.0 * 8192.0 * 4.0 * xyzNumberBytes + 65536.0;
    return d;
}

MemoryRoom availableMemory() {
    MemoryRoom room;
    std::ifstream meminfo("/proc/meminfo");
    std::string key, unit;
    double kib = 0.0;
    while (meminfo >> key >> kib >> unit)
        if (key == "MemAvailable:") {
            room.bytes = kib * 1024.0;
            break;
        }
    if (room.bytes <= 0.0) {
        const long pages = sysconf(_SC_AVPHYS_PAGES), size = sysconf(_SC_PAGESIZE);
        room.bytes = pages > 0 && size > 0 ? double(pages) * double(size) : 0.0;
    }
    auto tighter = [&room](double bytes, const char* whose) {
        if (bytes >= 0.0 && (room.bytes <= 0.0 || bytes < room.bytes)) room = {bytes, whose};
    };
    tighter(cgroupRoom(), "the process's cgroup leaves");
    // The address space: the limit less what the process has mapped already (VmSize).
    rlimit as{};
    if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY) {
        std::ifstream status("/proc/self/status");
        std::string line;
        double mapped = 0.0;
        while (std::getline(status, line))
            if (line.rfind("VmSize:", 0) == 0) mapped = std::stod(line.substr(7)) * 1024.0;
        tighter(std::max(0.0, double(as.rlim_cur) - mapped), "ulimit -v leaves");
    }
    return room;
}

double freeDiskBytes(const std::filesystem::path& dir) {
    std::filesystem::path p = std::filesystem::absolute(dir);
    std::error_code ec;
    while (!std::filesystem::exists(p, ec) && p.has_parent_path() && p != p.parent_path())
        p = p.parent_path();
    struct statvfs fs {};
    if (::statvfs(p.c_str(), &fs) != 0) return -1.0;
    return double(fs.f_bavail) * double(fs.f_frsize);
}

std::string showBytes(double bytes) {
    static const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    int u = 0;
    while (bytes >= 1024.0 && u < 6)
        bytes /= 1024.0, ++u;
    // Two significant digits below 10 ("3.4 MiB"), whole units above ("38 GiB", "1000 MiB").
    char text[32];
    std::snprintf(text, sizeof text, u > 0 && bytes < 9.95 ? "%.2g %s" : "%.0f %s", bytes,
                  units[u]);
    return text;
}

std::string memoryRefusal(const Scene& scene, const MemoryEstimate& need, const MemoryRoom& room) {
    if (!(room.bytes > 0.0) || need.total() <= room.bytes) return "";
    const int n = scene.state.particles.empty() ? scene.state.n : int(scene.state.particles.size());
    std::string key, hint;
    if (need.engine >= need.analysis) {
        key = scene.state.particles.empty() ? "state.n = " + std::to_string(n)
                                            : "state.particles (" + std::to_string(n) + " bodies)";
        hint = "use fewer bodies";
    } else {
        // The correlators' levels hold lags_per_level samples of each followed body (the samples
        // themselves are not kept: their number enters as the levels' logarithm).
        const auto& a = scene.analysis;
        const int followed = a.follow_bodies > 0 ? std::min(n, a.follow_bodies) : n;
        key = "analysis.follow_bodies, analysis.lags_per_level (" + std::to_string(followed) +
              " bodies followed, " + std::to_string(a.lags_per_level) + " lags a level)";
        hint = "follow fewer bodies or use fewer lags a level";
    }
    return key + ": the run needs about " + showBytes(need.total()) + " of memory (engine " +
           showBytes(need.engine) + ", analysis " + showBytes(need.analysis) + ") and " +
           room.whose + " " + showBytes(room.bytes) + " available: " + hint;
}

DiskVerdict diskVerdict(const Scene& scene, const DiskEstimate& need, double written,
                        double freeBytes, const std::filesystem::path& dir) {
    const double left = std::max(0.0, need.total() - written);
    if (freeBytes < 0.0 || left <= 0.5 * freeBytes) return {};
    // The key behind the largest file.
    std::string key = "output.trajectory_every_fs";
    double largest = need.trajectory;
    if (need.restart > largest) key = "output.restart_every_ps", largest = need.restart;
    if (need.thermo > largest) key = "output.thermo_every_fs", largest = need.thermo;
    if (need.results > largest) key = "state.n", largest = need.results;
    (void)scene;
    const std::string where = dir.string();
    std::string parts = need.trajectoryName + " " + showBytes(need.trajectory);
    if (need.restart > 0.0) parts += ", restart.bin " + showBytes(need.restart);
    if (need.thermo > 0.0) parts += ", thermo.csv " + showBytes(need.thermo);
    const std::string what =
        "the run will write about " + showBytes(left) + " into " + where + " (" + parts + ")";
    if (left > freeBytes)
        return {DiskVerdict::Kind::Refuse, key + ": " + what + " and its file system has " +
                                               showBytes(freeBytes) +
                                               " free: write less often, or choose another --out"};
    return {DiskVerdict::Kind::Warn,
            what + ", more than half of the " + showBytes(freeBytes) + " free on its file system"};
}

void checkResources(const Scene& scene, const std::filesystem::path& dir, bool continuing) {
    // The engine's own limit, which it would meet only after the initial state was built.
    const int n = scene.state.particles.empty() ? scene.state.n : int(scene.state.particles.size());
    if (scene.engine == "dmd" && n > dmd::Agendas::maxBodies)
        throw SceneError("run: state.n = " + std::to_string(n) + ": DMD runs at most " +
                         std::to_string(dmd::Agendas::maxBodies) +
                         " bodies (an agenda keeps an event's partner in 26 bits)");
    const std::string memory = memoryRefusal(scene, memoryEstimate(scene), availableMemory());
    if (!memory.empty()) throw SceneError("run: " + memory);
    double written = 0.0;
    if (continuing)
        for (const char* name : {"trajectory.xyz", "trajectory.gsd", "thermo.csv", "restart.bin"})
            written += fileSize(dir / name);
    const DiskVerdict disk =
        diskVerdict(scene, diskEstimate(scene), written, freeDiskBytes(dir), dir);
    if (disk.kind == DiskVerdict::Kind::Refuse) throw SceneError("run: " + disk.message);
    if (disk.kind == DiskVerdict::Kind::Warn)
        std::fprintf(stderr, "terrace: warning: %s\n", disk.message.c_str());
}

} // namespace terrace::cli
