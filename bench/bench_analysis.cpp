// Question: what does the analysis of a run cost per sample, as the run goes? CPU time of one
// sample handed to the product's accumulators (analysis/run_analysis.hpp) at the scene defaults
// (8 blocks, lags up to half a run of 10⁵ samples, 16 lags per level, 4096 followed bodies,
// g(r) out to 5σ every 10th sample), for N = 512 and 32 768 rods at ρ* = 0.5:
//
//   time_correlations   VACF, OACF and MSD of the followed bodies (streaming_correlations.hpp),
//                       the part whose linear lags are summed by FFT over windows
//   run_analysis        everything a run's sample costs, g(r) frames included
//
// Samples are free flights of random rods, cycled from a few stored ones with their times moved
// on (the cost does not depend on the physics, only on N and the plan). One number per case and
// N: microseconds of CPU time per sample (one sample per iteration).
#include "analysis/run_analysis.hpp"
#include "analysis/streaming_correlations.hpp"
#include "core/units.hpp"
#include <benchmark/benchmark.h>
#include <cmath>
#include <map>
#include <random>

using namespace terrace;
using namespace terrace::analysis;

namespace {

constexpr long plannedSamples = 100000;
constexpr int storedSamples = 8;
constexpr double interval = 0.1;   // time units = 10 fs
constexpr double sigma = 3.035;    // Å, the rods' σ
constexpr int followBodies = 4096; // the scene default

double boxFor(int n) {
    return std::cbrt(n / 0.5) * sigma; // ρ* = 0.5
}

/// A few samples of n free rods (positions drifting, axes turning a little per sample).
const std::vector<Snapshot>& samples(int n) {
    static std::map<int, std::vector<Snapshot>> cache;
    auto& s = cache[n];
    if (!s.empty()) return s;
    std::mt19937_64 rng(n);
    std::normal_distribution<double> g(0.0, 1.0);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double length = boxFor(n);
    s.resize(storedSamples);
    for (auto& f : s)
        f.boxLength = length;
    for (int i = 0; i < n; ++i) {
        Vec3 r(u(rng) * length, u(rng) * length, u(rng) * length);
        const Vec3 v = Vec3(g(rng), g(rng), g(rng)) * 0.5;
        Vec3 axis = Vec3(g(rng), g(rng), g(rng)).normalized();
        const Vec3 turn = Vec3(g(rng), g(rng), g(rng)) * 0.05;
        for (auto& f : s) {
            f.position.push_back(r);
            f.velocity.push_back(v);
            f.axis.push_back(axis);
            f.omega.push_back(turn);
            r += v * interval;
            axis = (axis + turn.cross(axis)).normalized();
        }
    }
    return s;
}

StreamingOptions defaults() {
    StreamingOptions o;
    o.rdfMaxAngstrom = 5.0 * sigma;
    o.rdfEvery = 10;
    o.followBodies = followBodies;
    return o;
}

void time_correlations(benchmark::State& state) {
    const int n = static_cast<int>(state.range(0));
    const auto& stored = samples(n);
    StreamingCorrelationPlan plan;
    plan.samples = plannedSamples;
    plan.blocks = 8;
    plan.maxLag = static_cast<int>(plannedSamples / 2);
    plan.followBodies = followBodies;
    StreamingCorrelations c(n, units::toPs(interval), plan);
    // The followed bodies alone, as the run driver hands them over.
    std::vector<Snapshot> followed(storedSamples);
    for (int k = 0; k < storedSamples; ++k) {
        followed[k].boxLength = stored[k].boxLength;
        for (const int i : c.followedBodies()) {
            followed[k].position.push_back(stored[k].position[i]);
            followed[k].velocity.push_back(stored[k].velocity[i]);
            followed[k].axis.push_back(stored[k].axis[i]);
        }
    }
    long k = 0;
    for (auto _ : state) {
        Snapshot& f = followed[k % storedSamples];
        f.time = double(k++) * interval;
        c.addFollowed(f);
    }
}

void run_analysis(benchmark::State& state) {
    const int n = static_cast<int>(state.range(0));
    auto stored = samples(n);
    RunAnalysis a(n, boxFor(n), units::toPs(interval), plannedSamples, defaults());
    long k = 0;
    for (auto _ : state) {
        Snapshot& f = stored[k % storedSamples];
        f.time = double(k++) * interval;
        a.add(f);
    }
}

} // namespace

BENCHMARK(time_correlations)->Arg(512)->Arg(32768)->Unit(benchmark::kMicrosecond);
BENCHMARK(run_analysis)->Arg(512)->Arg(32768)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
