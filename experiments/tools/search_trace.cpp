#include "experiments/tools/search_trace.hpp"
#include "core/initial_state.hpp"
#include "core/linear_rotor.hpp"
#include "core/rod_potential.hpp"
#include "core/scene.hpp"
#include "core/system.hpp"
#include "core/units.hpp"
#include "dmd/root_search.hpp"
#include "dmd/scene_engine.hpp"
#include "dmd/settings.hpp"
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

namespace terrace::experiments {
namespace {

using Rods = System<LinearRotor, RodPotential>;

/// The search is followed over this many horizons, as a chain of resumed virtual events would
/// follow it, so that the figure shows several grid points before the root.
constexpr double windowInHorizons = 10.0;
/// Points per fs of the finely sampled exact curve and of each interpolant.
constexpr int curvePointsPerFs = 20;

struct Trace {
    std::vector<dmd::PairSample> samples; // in call order
    dmd::SearchResult result;
    int n = 0; // the pair's terrace at the start
    double lower = 0, upper = 0;
};

/// U and dU/dt of the pair (i, j) a time τ after the start, along free motion (as the engine).
auto pairEvaluation(const Rods& sys, int i, int j) {
    const auto bi = sys.bodies[i], bj = sys.bodies[j];
    const Vec3 r0 = sys.box.minimumImage(bi.r - bj.r), w = bi.v - bj.v;
    return [&sys, bi, bj, r0, w](double tau) {
        auto ci = bi, cj = bj;
        freeMove<LinearRotor>(ci, sys.body, tau);
        freeMove<LinearRotor>(cj, sys.body, tau);
        const PairForce f = sys.potential.evaluate(r0 + w * tau, ci.s, cj.s);
        return dmd::PairSample{tau, f.U, dUdt(f, w, ci.w, cj.w)};
    };
}

Trace traceSearch(const Rods& sys, const dmd::DmdSettings& settings,
                  const dmd::SearchSettings& search, int i, int j) {
    Trace t;
    auto exact = pairEvaluation(sys, i, j);
    auto recorded = [&](double tau) {
        const dmd::PairSample p = exact(tau);
        t.samples.push_back(p);
        return p;
    };
    const dmd::PairSample start = recorded(0.0);
    t.n = settings.levels.terraceOf(start.U, start.dUdt);
    t.lower = settings.levels.lower(t.n);
    t.upper = settings.levels.upper(t.n);
    t.result = dmd::findTerraceExit(recorded, start, t.lower, t.upper,
                                    windowInHorizons * search.maxStep, search);
    return t;
}

std::vector<dmd::PairSample> gridPoints(const Trace& t) {
    std::vector<dmd::PairSample> grid;
    for (const auto& p : t.samples)
        if (grid.empty() || p.t > grid.back().t) grid.push_back(p);
    return grid;
}

/// Steps of the algorithm a trace shows: grid points, and interpolant extrema examined.
int illustrativeness(const Trace& t) {
    if (t.result.side == dmd::ExitSide::None) return -1;
    const auto grid = gridPoints(t);
    const int inner = int(t.samples.size() - grid.size());
    const int g = int(grid.size());
    return (g > 8 ? 8 - g : g) + (inner > 0 ? 3 : 0) + (t.n != 0 ? 2 : 0);
}

std::ofstream openCsv(const std::filesystem::path& p, const char* header) {
    std::ofstream out(p);
    if (!out) throw std::runtime_error(p.string() + ": cannot write");
    out.precision(10);
    out << header << '\n';
    return out;
}

} // namespace

void writeSearchTrace(const std::filesystem::path& dir, double dVInKT) {
    Scene scene = defaultScene();
    scene.dmd["dV"] = dVInKT;
    const Rods sys = buildInitialState<LinearRotor>(scene, rodPotential(scene));
    const auto settings = dmd::readDmdSettings(scene.dmd, sys.potential, sys.kT, sys.box.length);
    dmd::SearchSettings search; // as the engine sets it up (dmd/engine.hpp)
    search.maxStep = settings.horizon;
    search.nudge = dmd::nudgeFraction * settings.horizon;
    search.grazeWindow = dmd::grazeFraction * settings.levels.smallestStep();

    Trace best;
    int bestScore = -1, bi = -1, bj = -1;
    for (int i = 0; i < sys.size(); ++i)
        for (int j = i + 1; j < sys.size(); ++j) {
            if (sys.box.minimumImage(sys.bodies[i].r - sys.bodies[j].r).norm() > settings.rm)
                continue;
            Trace t = traceSearch(sys, settings, search, i, j);
            const int score = illustrativeness(t);
            if (score > bestScore) bestScore = score, best = std::move(t), bi = i, bj = j;
        }
    if (bestScore < 0) throw std::runtime_error("fig2: no pair's search found a root");

    std::filesystem::create_directories(dir);
    const auto fs = [](double t) { return units::toFs(t); };
    const double tRoot = best.result.t;
    const double level = best.result.side == dmd::ExitSide::Lower ? best.lower : best.upper;
    const auto grid = gridPoints(best);
    const double tShow = grid.back().t;
    auto exact = pairEvaluation(sys, bi, bj);
    {
        auto out = openCsv(dir / "fig2_exact.csv", "t_fs,U");
        const int n = std::max(2, int(fs(tShow) * curvePointsPerFs));
        for (int k = 0; k <= n; ++k) {
            const double t = tShow * k / n;
            out << fs(t) << ',' << exact(t).U << '\n';
        }
    }
    {
        auto gridOut = openCsv(dir / "fig2_grid.csv", "t_fs,U,dUdt_per_fs");
        auto cubicOut = openCsv(dir / "fig2_cubic.csv", "t_fs,U_cubic");
        auto extremaOut = openCsv(dir / "fig2_extrema.csv", "t_fs,U_cubic");
        for (std::size_t k = 0; k < grid.size(); ++k) {
            gridOut << fs(grid[k].t) << ',' << grid[k].U << ',' << grid[k].dUdt / fs(1.0) << '\n';
            if (k == 0) continue;
            const dmd::detail::HermiteCubic cubic(grid[k - 1], grid[k]);
            const int n = std::max(8, int(fs(cubic.h) * curvePointsPerFs));
            for (int m = 0; m <= n; ++m) {
                const double s = cubic.h * m / n;
                cubicOut << fs(cubic.t0 + s) << ',' << cubic.value(s) << '\n';
            }
            cubicOut << '\n';
            std::array<double, 2> ext{};
            const int ne = cubic.extrema(ext);
            for (int e = 0; e < ne; ++e)
                extremaOut << fs(cubic.t0 + ext[e]) << ',' << cubic.value(ext[e]) << '\n';
        }
    }
    int inner = 0;
    {
        auto out = openCsv(dir / "fig2_inner.csv", "t_fs,U");
        double latest = -1.0;
        for (const auto& p : best.samples) {
            if (p.t > latest) {
                latest = p.t;
                continue;
            }
            out << fs(p.t) << ',' << p.U << '\n';
            ++inner;
        }
    }
    openCsv(dir / "fig2_root.csv", "t_fs,U,level")
        << fs(tRoot) << ',' << exact(tRoot).U << ',' << level << '\n';
    nlohmann::json info = {{"scene", scene.name},
                           {"seed", scene.seed},
                           {"pair", {bi, bj}},
                           {"dV_kT", dVInKT},
                           {"terrace", best.n},
                           {"lower_level", best.lower},
                           {"upper_level", best.upper},
                           {"exit", best.result.side == dmd::ExitSide::Lower ? "lower" : "upper"},
                           {"root_fs", fs(tRoot)},
                           {"max_step_fs", fs(search.maxStep)},
                           {"nudge_fs", fs(search.nudge)},
                           {"graze_window", search.grazeWindow},
                           {"grid_points", grid.size()},
                           {"inner_samples", inner},
                           {"evaluations", best.samples.size()}};
    std::ofstream(dir / "fig2_info.json") << info.dump(2) << '\n';
}

} // namespace terrace::experiments
