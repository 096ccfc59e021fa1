// SMD speed: steps per second and pair evaluations (pairs within r_u) per second, counted by the
// engine, for
//   - the paper's dense rods (ρ* = 0.5, T* = 1.4, dt = 1.8 fs, smoothed 2.5-3σ), N = 512, 4096;
//   - Lennard-Jones spheres at the standard LJ benchmark state point (ρ* = 0.8442, T* = 1.44,
//     skin 0.3σ, dt = 0.005τ), N = 512, 32000, with the cutoff ending at r_u = 2.5σ (switched
//     from 2σ, so that the same pairs interact as under a plain 2.5σ cut);
//   - the LAMMPS comparison input: LJ spheres, N = 512, ρ* = 0.5, T* = 1.4, smoothed 2.5-3σ,
//     dt = 0.005τ (experiments/lammps/ runs LAMMPS on it side by side).
// LJ runs in reduced units: ε = 1 kJ/mol, σ = 1 Å, m = 1 g/mol, so τ = 1 time unit = 100 fs.
// Every run first melts the lattice start (warm-up steps, not timed).
#include "core/initial_state.hpp"
#include "core/linear_rotor.hpp"
#include "core/sphere.hpp"
#include "smd/engine.hpp"
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
    smd::Engine<K, Smoothed<P>> engine(buildInitialState<K, Smoothed<P>>(sc, model), sc);
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
    tuned.smd.skin = state.range(0) / 100.0; // σ/100: LAMMPS's 0.3σ by default
    runSteps<Sphere>(state, tuned, ljPotential(tuned), 500);
}

} // namespace

BENCHMARK(denseRods)->Arg(512)->Arg(4096)->Unit(benchmark::kMicrosecond)->MinTime(2.0);
BENCHMARK(ljStandard)->Arg(512)->Arg(32000)->Unit(benchmark::kMicrosecond)->MinTime(2.0);
BENCHMARK(ljLammpsInput)->Arg(30)->Unit(benchmark::kMicrosecond)->MinTime(2.0);
BENCHMARK_MAIN();
