// How long does the analysis of one run take? CPU time of each correlation of writeCorrelations
// on the samples of a dense-rods-sized run (N bodies, 1001 samples 10 fs apart = 10 ps), free
// rotors standing in for the trajectory (the cost does not depend on the physics). One number
// per correlation and N: milliseconds per call.
#include "analysis/dynamic_correlations.hpp"
#include "analysis/rdf.hpp"
#include "core/linear_rotor.hpp"
#include <benchmark/benchmark.h>
#include <map>
#include <random>

using namespace terrace;
using namespace terrace::analysis;

namespace {

constexpr int samples = 1001, maxLag = 500, blocks = 8;
constexpr double interval = 0.1; // time units = 10 fs

const std::vector<Snapshot>& run(int n) {
    static std::map<int, std::vector<Snapshot>> cache;
    auto& s = cache[n];
    if (!s.empty()) return s;
    std::mt19937_64 rng(n);
    std::normal_distribution<double> g(0.0, 1.0);
    const double length = std::cbrt(n / 0.5) * 3.035; // ρ* = 0.5, σ = 3.035 Å
    s.resize(samples);
    for (int k = 0; k < samples; ++k)
        s[k].time = k * interval, s[k].boxLength = length;
    for (int i = 0; i < n; ++i) {
        LinearRotor::State b;
        b.r = Vec3(g(rng), g(rng), g(rng)) * length;
        b.v = Vec3(g(rng), g(rng), g(rng)) * 0.5;
        b.s = Vec3(g(rng), g(rng), g(rng)).normalized();
        b.w = b.s.unitOrthogonal() * 1.9 * g(rng);
        for (int k = 0; k < samples; ++k) {
            LinearRotor::State at = b;
            freeMove<LinearRotor>(at, BodyParams{18.0, Vec3(1.154, 1.154, 0.0)}, k * interval);
            s[k].position.push_back(at.r);
            s[k].velocity.push_back(at.v);
            s[k].axis.push_back(at.s);
            s[k].omega.push_back(at.w);
        }
    }
    return s;
}

void rdf(benchmark::State& state) {
    const auto& s = run(static_cast<int>(state.range(0)));
    for (auto _ : state)
        benchmark::DoNotOptimize(radialDistribution(s, 0.05, blocks));
}
void vacf(benchmark::State& state) {
    const auto& s = run(static_cast<int>(state.range(0)));
    for (auto _ : state)
        benchmark::DoNotOptimize(velocityAutocorrelation(s, maxLag, blocks));
}
void oacf(benchmark::State& state) {
    const auto& s = run(static_cast<int>(state.range(0)));
    for (auto _ : state)
        benchmark::DoNotOptimize(orientationalAutocorrelation(s, maxLag, blocks));
}
void msd(benchmark::State& state) {
    const auto& s = run(static_cast<int>(state.range(0)));
    for (auto _ : state)
        benchmark::DoNotOptimize(meanSquaredDisplacement(s, maxLag, blocks));
}

} // namespace

BENCHMARK(rdf)->Arg(128)->Arg(512)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();
BENCHMARK(vacf)->Arg(128)->Arg(512)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();
BENCHMARK(oacf)->Arg(128)->Arg(512)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();
BENCHMARK(msd)->Arg(128)->Arg(512)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();
BENCHMARK_MAIN();
