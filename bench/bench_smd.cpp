// SMD speed: steps per second and pair evaluations (pairs within r_u) per second, counted by the
// engine, for
//   - the paper's dense rods (ρ* = 0.5, T* = 1.4, dt = 1.8 fs, smoothed 2.5-3σ), N = 512, 4096;
//   - Lennard-Jones spheres at the standard LJ benchmark state point (ρ* = 0.8442, T* = 1.44,
//     skin 0.3σ, dt = 0.005τ), N = 512, 32000, with the cutoff ending at r_u = 2.5σ (switched
//     from 2σ, so that the same pairs interact as under a plain 2.5σ cut);
//   - the LAMMPS comparison input: LJ spheres, N = 512, ρ* = 0.5, T* = 1.4, smoothed 2.5-3σ,
//     dt = 0.005τ (experiments/lammps/ runs LAMMPS on it side by side);
//   - the LJ pair loop alone, scalar against AVX2 (smd/lj_pairs_avx2.hpp), and the list build
//     alone, on the liquid of experiments/lammps/tabulated.sh (ρ* = 0.8, T* = 0.9, smoothed
//     2.5-3σ, skin 0.3σ) melted from the lattice: listed pairs per second.
// LJ runs in reduced units: ε = 1 kJ/mol, σ = 1 Å, m = 1 g/mol, so τ = 1 time unit = 100 fs.
// Every run first melts the lattice start (warm-up steps, not timed).
#include "core/initial_state.hpp"
#include "core/linear_rotor.hpp"
#include "core/sphere.hpp"
#include "smd/scene_engine.hpp"
#include <benchmark/benchmark.h>
#include <string>

using namespace terrace;

namespace {

Scene scene(const std::vector<std::string>& overrides) {
    return sceneFromJson(nlohmann::json::object(), "<bench>", overrides);
}

Scene rodScene(int n) {
    return scene({"engine=smd", "state.n=" + std::to_string(n), "state.density=0.5",
                  "state.temperature=1.4", "smd.dt_fs=1.8"});
}

Scene ljScene(int n, double density, double temperature, double rl, double ru) {
    return scene({"engine=smd", "body.kind=sphere", "body.mass=1", "body.inertia=[0,0,0]",
                  "potential.kind=lj", "potential.epsilon=1", "potential.sigma=1",
                  "state.n=" + std::to_string(n), "state.density=" + std::to_string(density),
                  "state.temperature=" + std::to_string(temperature), "smd.dt_fs=0.5",
                  "smd.skin=0.3",
                  "potential.cutoff=[" + std::to_string(rl) + "," + std::to_string(ru) + "]"});
}

template <BodyKind K, PairPotential P>
void runSteps(benchmark::State& state, const Scene& sc, const P& bare, int warmup) {
    const Smoothed<P> model{bare, sceneCutoff(sc)};
    smd::SceneEngine<K, Smoothed<P>> engine(buildInitialState<K, Smoothed<P>>(sc, model), sc);
    for (int k = 0; k < warmup; ++k)
        engine.step();
    const long steps0 = engine.steps(), pairs0 = engine.pairEvaluations();
    const long rebuilds0 = engine.neighbourRebuilds();
    for (auto _ : state)
        engine.step();
    const double steps = double(engine.steps() - steps0);
    const double n = engine.system().size();
    using C = benchmark::Counter;
    state.counters["steps/s"] = C(steps, C::kIsRate);
    state.counters["pair_evals/s"] = C(double(engine.pairEvaluations() - pairs0), C::kIsRate);
    state.counters["atom_steps/s"] = C(steps * n, C::kIsRate);
    state.counters["pairs/body"] = double(engine.pairEvaluations() - pairs0) / (steps * n);
    state.counters["steps/rebuild"] =
        steps / std::max(1.0, double(engine.neighbourRebuilds() - rebuilds0));
}

void denseRods(benchmark::State& state) {
    const Scene sc = rodScene(int(state.range(0)));
    runSteps<LinearRotor>(state, sc, rodPotential(sc), 300);
}

void ljStandard(benchmark::State& state) {
    const Scene sc = ljScene(int(state.range(0)), 0.8442, 1.44, 2.0, 2.5);
    runSteps<Sphere>(state, sc, ljPotential(sc), 200);
}

void ljLammpsInput(benchmark::State& state) {
    const Scene sc = ljScene(512, 0.5, 1.4, 2.5, 3.0);
    Scene tuned = sc;
    tuned.smd["skin"] = state.range(0) / 100.0; // σ/100: LAMMPS's 0.3σ by default
    runSteps<Sphere>(state, tuned, ljPotential(tuned), 500);
}

/// The liquid of experiments/lammps/tabulated.sh after `warmup` steps from the lattice, with its
/// Verlet list and the positions per list slot.
struct ListedLiquid {
    System<Sphere, Smoothed<LJPotential>> sys;
    smd::NeighbourList list;
    std::vector<Vec3> r, x; // per body; per slot (r - offset)
};

ListedLiquid listedLiquid(int n, int warmup) {
    const Scene sc = ljScene(n, 0.8, 0.9, 2.5, 3.0);
    const Smoothed<LJPotential> model{ljPotential(sc), sceneCutoff(sc)};
    smd::SceneEngine<Sphere, Smoothed<LJPotential>> engine(
        buildInitialState<Sphere, Smoothed<LJPotential>>(sc, model), sc);
    for (int k = 0; k < warmup; ++k)
        engine.step();
    ListedLiquid liquid{engine.system(), {}, {}, {}};
    liquid.list.skin = engine.parameters().skin;
    liquid.list.reach = model.range() + liquid.list.skin;
    for (const auto& b : liquid.sys.bodies)
        liquid.r.push_back(b.r);
    smd::build(liquid.list, liquid.sys.box, liquid.r);
    for (std::size_t a = 0; a < liquid.r.size(); ++a)
        liquid.x.push_back(liquid.r[liquid.list.order[a]] - liquid.list.offset[a]);
    return liquid;
}

/// Arg 0: the scalar loop, 1: the AVX2 loop (skipped without AVX2).
void ljPairLoop(benchmark::State& state) {
    const bool avx2 = state.range(1) == 1;
    if (avx2 && !smd::avx2Available()) return state.SkipWithError("no AVX2 loops");
    const ListedLiquid liquid = listedLiquid(int(state.range(0)), 400);
    smd::Forces f;
    for (auto _ : state) {
        f.reset(liquid.x.size());
        if (avx2)
            smd::accumulateListedPairs<LJPotential>(f, liquid.sys.potential, liquid.list, liquid.x,
                                                    liquid.x);
        else
            smd::accumulateListedPairsScalar<LJPotential>(f, liquid.sys.potential, liquid.list,
                                                          liquid.x, liquid.x);
        benchmark::DoNotOptimize(f.potential);
    }
    using C = benchmark::Counter;
    state.counters["listed_pairs/s"] =
        C(double(liquid.list.pairCount()) * double(state.iterations()), C::kIsRate);
}

/// Arg 0: the scalar cell scan, 1: the AVX2 one.
void ljListBuild(benchmark::State& state) {
    const bool avx2 = state.range(1) == 1;
    if (avx2 && !smd::avx2Available()) return state.SkipWithError("no AVX2 loops");
    ListedLiquid liquid = listedLiquid(int(state.range(0)), 400);
    for (auto _ : state)
        smd::build(liquid.list, liquid.sys.box, liquid.r, avx2);
    using C = benchmark::Counter;
    state.counters["listed_pairs/s"] =
        C(double(liquid.list.pairCount()) * double(state.iterations()), C::kIsRate);
}

} // namespace

// Both sizes, each with the scalar loop (0) and the AVX2 loop (1).
void scalarAndAvx2(benchmark::internal::Benchmark* b) {
    b->ArgsProduct({{512, 32000}, {0, 1}})->Unit(benchmark::kMicrosecond)->MinTime(1.0);
}
BENCHMARK(ljPairLoop)->Apply(scalarAndAvx2);
BENCHMARK(ljListBuild)->Apply(scalarAndAvx2);
BENCHMARK(denseRods)->Arg(512)->Arg(4096)->Unit(benchmark::kMicrosecond)->MinTime(2.0);
BENCHMARK(ljStandard)->Arg(512)->Arg(32000)->Unit(benchmark::kMicrosecond)->MinTime(2.0);
BENCHMARK(ljLammpsInput)->Arg(30)->Unit(benchmark::kMicrosecond)->MinTime(2.0);
BENCHMARK_MAIN();
