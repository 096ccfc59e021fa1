// Questions (issue "DMD engine", benchmarks): how many events and collisions per CPU second does
// the DMD engine process on the paper's dense rods (N 512, ρ* 0.5, T* 1.4) at ΔV = 2, 1, ½, ¼ kT;
// what do the bounded priority queue (vs a binary heap), lazy invalidation (vs eager) and the
// hold-time screen save in one and the same run; does the cost per event stay flat from N = 512 to
// 262144; and how much memory does a body cost? Counters are per CPU second (Google Benchmark's
// default clock).
#include "core/initial_state.hpp"
#include "core/linear_rotor.hpp"
#include "dmd/scene_engine.hpp"
#include "dmd/testing.hpp"
#include <benchmark/benchmark.h>
#include <cmath>
#include <ctime>
#include <sys/resource.h>

using terrace::dmd::testing::Probe;

namespace {

using namespace terrace;
using RodEngine = dmd::SceneEngine<LinearRotor, RodPotential>;

Scene denseRods(int n, double dV, const char* queue = "bpq", const char* invalidation = "lazy") {
    Scene s = defaultScene();
    s.state.n = n;
    s.dmd["dV"] = dV;
    s.dmd["queue"] = queue;
    s.dmd["invalidation"] = invalidation;
    return s;
}

/// Equilibrates with rescaling at sample times (0.5 ps), as a production run would start.
RodEngine equilibrated(const Scene& s) {
    RodEngine e(buildInitialState<LinearRotor>(s, rodPotential(s)), s);
    for (int k = 1; k <= 10; ++k) {
        e.advanceTo(units::fromFs(50.0 * k));
        e.rescaleTemperature(s.kT());
    }
    return e;
}

std::uint64_t collisions(const dmd::EventCounts& c) {
    return c.up + c.down + c.reflect;
}

double cpuSeconds() {
    return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

// Dense rods at ΔV = dV/100 kT: events and collisions per CPU second, CPU seconds per simulated
// ps, collisions per simulated ps (the paper: 3.5e4 at kT, 4.7e4 at kT/2) and the relative energy
// error over the run.
void DenseRods(benchmark::State& state) {
    const double dV = state.range(0) / 100.0;
    RodEngine e = equilibrated(denseRods(512, dV));
    const double e0 = e.kineticEnergy() + e.potentialEnergy();
    const dmd::EventCounts c0 = Probe::counts(e);
    const double t0 = e.time(), span = units::fromPs(0.5);
    const double cpu0 = cpuSeconds();
    for (auto _ : state)
        e.advanceTo(e.time() + span);
    const double cpu = cpuSeconds() - cpu0;
    const dmd::EventCounts& c = Probe::counts(e);
    const double ps = units::toPs(e.time() - t0);
    // The engine alone: the CLI's cpu_seconds_per_ps also holds the analysis of the samples.
    state.counters["cpu_s_per_ps"] = cpu / ps;
    state.counters["events"] =
        benchmark::Counter(double(c.total() - c0.total()), benchmark::Counter::kIsRate);
    state.counters["collisions"] =
        benchmark::Counter(double(collisions(c) - collisions(c0)), benchmark::Counter::kIsRate);
    state.counters["coll_per_ps"] = double(collisions(c) - collisions(c0)) / ps;
    state.counters["virtual_per_coll"] =
        double(c.virtualEvents - c0.virtualEvents) / double(collisions(c) - collisions(c0));
    state.counters["rel_energy_error"] =
        std::abs(e.kineticEnergy() + e.potentialEnergy() - e0) / std::abs(e0);
}
BENCHMARK(DenseRods)->Arg(200)->Arg(100)->Arg(50)->Arg(25)->Iterations(4)->Unit(
    benchmark::kMillisecond);

// The paper's two savings measured in one run on identical trajectories: CPU time of heap/lazy,
// bpq/lazy, tree/lazy and bpq/eager over the same simulated span (ΔV = kT/2), each over
// bpq/lazy's: above 1, bpq with lazy invalidation is the cheaper.
void QueueAndInvalidationRatios(benchmark::State& state) {
    const double span = units::fromPs(1.0);
    double heap = 0.0, bpq = 0.0, tree = 0.0, eager = 0.0;
    for (auto _ : state) {
        auto timeRun = [&](const char* queue, const char* invalidation) {
            RodEngine e = equilibrated(denseRods(512, 0.5, queue, invalidation));
            const double start = cpuSeconds();
            e.advanceTo(e.time() + span);
            return cpuSeconds() - start;
        };
        heap += timeRun("heap", "lazy");
        bpq += timeRun("bpq", "lazy");
        tree += timeRun("tree", "lazy");
        eager += timeRun("bpq", "eager");
    }
    state.counters["heap_over_bpq"] = heap / bpq;
    state.counters["tree_over_bpq"] = tree / bpq;
    state.counters["eager_over_lazy"] = eager / bpq;
}
BENCHMARK(QueueAndInvalidationRatios)->Iterations(2)->Unit(benchmark::kSecond);

// What the hold-time screen (dmd/terrace_hold.hpp) saves: CPU time and samples of U without it
// over those with it, over the same simulated span of the same start (ΔV = kT/2).
void HoldScreenRatio(benchmark::State& state) {
    const double span = units::fromPs(1.0);
    double screened = 0.0, searched = 0.0, samplesScreened = 0.0, samplesSearched = 0.0;
    for (auto _ : state) {
        auto timeRun = [&](bool screen, double& samples) {
            RodEngine e = equilibrated(denseRods(512, 0.5));
            Probe::setHoldScreen(e, screen);
            const double before = e.statistics()["search_evaluations"].get<double>();
            const double start = cpuSeconds();
            e.advanceTo(e.time() + span);
            samples += e.statistics()["search_evaluations"].get<double>() - before;
            return cpuSeconds() - start;
        };
        screened += timeRun(true, samplesScreened);
        searched += timeRun(false, samplesSearched);
    }
    state.counters["searched_over_screened"] = searched / screened;
    state.counters["samples_searched_over_screened"] = samplesSearched / samplesScreened;
}
BENCHMARK(HoldScreenRatio)->Iterations(2)->Unit(benchmark::kSecond);

// CPU time per event against N from a lattice start (ΔV = kT/2, bpq, lazy): an O(1) queue keeps
// it nearly flat. Every N is measured over the same stretch of simulated time, 40 to 40 + 5k fs
// after the start, because the mix of events (and so the cost of an average one) changes while
// the lattice melts: a fixed number of events would look at the melt for large N and at the
// liquid for small N. The synchronisation of all clocks at the end of each stretch is O(N),
// against the O(N) events in it.
void CostPerEvent(benchmark::State& state) {
    const int n = static_cast<int>(state.range(0));
    const Scene s = denseRods(n, 0.5);
    RodEngine e(buildInitialState<LinearRotor>(s, rodPotential(s)), s);
    e.advanceTo(units::fromFs(40.0));
    const std::uint64_t before = Probe::counts(e).total();
    for (auto _ : state)
        e.advanceTo(e.time() + units::fromFs(5.0));
    const double events = double(Probe::counts(e).total() - before);
    state.counters["events"] = benchmark::Counter(events, benchmark::Counter::kIsRate);
    state.counters["ns_per_event"] = benchmark::Counter(
        events * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.counters["engine_bytes_per_body"] = double(Probe::bytesReserved(e)) / n;
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    // Process-wide peak: meaningful for the largest N, which runs last.
    state.counters["peak_rss_bytes_per_body"] = usage.ru_maxrss * 1024.0 / n;
}
BENCHMARK(CostPerEvent)
    ->Arg(512)
    ->Arg(4096)
    ->Arg(32768)
    ->Arg(262144)
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
