// Question: what does one event cost in the DMD event queue — binary heap vs G. Paul's bounded
// priority queue, lazy vs eager invalidation — and does the bounded queue keep it flat in N?
// (paper, "Implementation of the event-driven simulation": ≈ 15 % of the total run time each.)
//
// Hold model of an event-driven calendar (J. G. Vaucher & P. Duval, Commun. ACM 18, 223 (1975)):
// N bodies with kPredictionsPerBody pending predictions each. One hold = pop the earliest valid
// event, schedule 1–3 new ones at now + delay (exponential or uniform, mean τ), and invalidate one
// random pending prediction per extra one, so that the number of valid predictions stays constant.
//   none  — pure hold, one pop and one push, nothing invalidated and no bookkeeping: the queue's
//           own cost and its scaling in N;
//   lazy  — invalidation bumps the prediction's counter; the stale entry stays queued and is
//           skipped when popped (DESIGN.md: per-particle counters), with removeIf cleanup if stale
//           entries ever outnumber valid ones kCleanupFactor − 1 to one;
//   eager — invalidation erases the entry through its handle.
// Reported per benchmark: ns per hold (CPU time), bytes per queued entry and per body; after the
// run, a table of ratios heap/bpq and eager/lazy for each N. The queue alone is timed here: in the
// engine, event processing between holds also competes for cache, so whole-run ratios are smaller.
//
// The engine's calendar holds one entry per body (dmd/schedule.hpp), which the tournament tree
// needs; the owner model is that calendar: N owners, one entry each. One hold = pop the earliest
// (owner i), give i a new entry at now + delay and, one hold in three (a collision), give a
// neighbour j of i (|i − j| ≤ 300, as the engine's Morton order puts partners) a new entry in place
// of its old one. The heap erases j's old entry through its handle first (eager); the tree
// overwrites it. Ratio tree/heap per N after the run.
#include "dmd/binary_heap_queue.hpp"
#include "dmd/bounded_priority_queue.hpp"
#include "dmd/tournament_queue.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <type_traits>
#include <unistd.h>
#include <vector>

namespace terrace::dmd {
namespace {

// As large as the engine's dmd::Event (48 B), so that bytes per body are the engine's.
struct HoldEvent {
    double time = 0.0;       // time units
    std::uint32_t id = 0;    // which prediction
    std::uint32_t stamp = 0; // the prediction's counter when scheduled (lazy invalidation)
    double payload[3] = {};  // what a DMD event carries besides: U, dU/dt, bodies, kind
    std::uint32_t partner = 0;
    std::uint32_t kind = 0;
};
static_assert(sizeof(HoldEvent) == 48);

enum class Invalidation { None, Lazy, Eager };
constexpr const char* name(Invalidation v) {
    return v == Invalidation::None ? "none" : v == Invalidation::Lazy ? "lazy" : "eager";
}

constexpr std::size_t kPredictionsPerBody = 12; // the 10–20 pending events per body
constexpr double kMeanDelay = 1.0;              // τ, time units; only ratios to it matter
constexpr double kEventsPerBin = 8.0;  // Paul: speed barely changes between ~5 and ~500 per bin
constexpr double kCleanupFactor = 3.0; // lazy cleanup once entries exceed 3× valid predictions
constexpr std::int64_t kTimedHolds = 2'000'000;
constexpr int kDelayTableBits = 12;
constexpr std::uint64_t kHoldSeed = 0x5eed'e7e4'7c0e'0001;

enum class Delays { Exponential, Uniform };

// xorshift64* (S. Vigna, ACM TOMS 42, 8 (2016)): cheap enough not to dominate the queue's cost.
struct Xorshift {
    std::uint64_t s;
    std::uint64_t next() {
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        return s * 0x2545F4914F6CDD1DULL;
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1p-53; } // [0, 1)
};

template <class Q> class HoldModel {
public:
    HoldModel(Q queue, Invalidation invalidation, Delays delays)
        : queue_(std::move(queue)), invalidation_(invalidation),
          eager_(invalidation == Invalidation::Eager), delays_(delays),
          delayTable_(quantiles(delays)) {}

    void schedule() {
        std::uint32_t id;
        if (!freeIds_.empty()) {
            id = freeIds_.back();
            freeIds_.pop_back();
        } else {
            id = static_cast<std::uint32_t>(predictions_.size());
            predictions_.emplace_back();
        }
        if (invalidation_ == Invalidation::None) { // no bookkeeping: time the queue alone
            queue_.push({now_ + delay(), id, 0, {}, id ^ 1u, 0});
            return;
        }
        Prediction& p = predictions_[id];
        const QueueHandle h = queue_.push({now_ + delay(), id, p.stamp, {}, id ^ 1u, 0});
        if (eager_) p.handle = h;
        p.validIndex = static_cast<std::uint32_t>(valid_.size());
        valid_.push_back(id);
    }

    void hold() {
        if (invalidation_ == Invalidation::None) {
            const HoldEvent e = queue_.top();
            queue_.pop();
            now_ = e.time;
            freeIds_.push_back(e.id);
            schedule();
            return;
        }
        for (;;) {
            const HoldEvent e = queue_.top();
            queue_.pop();
            if (e.stamp == predictions_[e.id].stamp) {
                now_ = e.time;
                retire(e.id);
                break;
            }
            ++stalePops_;
        }
        // 1–3 new predictions and one fewer invalidations keep the valid count fixed.
        const int pushes = 1 + static_cast<int>(rng_.next() % 3);
        for (int k = 0; k < pushes; ++k)
            schedule();
        for (int k = 1; k < pushes; ++k) {
            const std::uint32_t victim = valid_[rng_.next() % valid_.size()];
            if (eager_) queue_.erase(predictions_[victim].handle);
            retire(victim);
        }
        if (invalidation_ == Invalidation::Lazy && queue_.size() > kCleanupFactor * valid_.size()) {
            queue_.removeIf(
                [this](const HoldEvent& e) { return e.stamp != predictions_[e.id].stamp; });
            ++cleanups_;
        }
    }

    // Rebins the bounded queue for the entries now queued (the engine's retune after measuring
    // the event rate): pending times near "now" have density size/τ for both delay laws.
    void tune() {
        if constexpr (requires { queue_.retune(1.0, std::size_t{1}); }) {
            const double width = kEventsPerBin * kMeanDelay / static_cast<double>(queue_.size());
            const double window = (delays_ == Delays::Exponential ? 4.0 : 2.0) * kMeanDelay;
            queue_.retune(width, static_cast<std::size_t>(std::ceil(window / width)));
        }
    }

    const Q& queue() const { return queue_; }
    std::size_t stalePops() const { return stalePops_; }
    std::size_t cleanups() const { return cleanups_; }

private:
    double delay() { return delayTable_[rng_.next() >> (64 - kDelayTableBits)]; }

    // Delays drawn from 2^12 equally likely quantiles of the delay law: a table lookup instead of a
    // logarithm per event keeps the random numbers from diluting the queue's cost.
    static std::vector<double> quantiles(Delays delays) {
        std::vector<double> table(std::size_t{1} << kDelayTableBits);
        for (std::size_t k = 0; k < table.size(); ++k) {
            const double u = (static_cast<double>(k) + 0.5) / static_cast<double>(table.size());
            table[k] =
                delays == Delays::Exponential ? -kMeanDelay * std::log1p(-u) : 2.0 * kMeanDelay * u;
        }
        return table;
    }

    void retire(std::uint32_t id) {
        Prediction& p = predictions_[id];
        ++p.stamp;
        const std::uint32_t last = valid_.back();
        valid_[p.validIndex] = last;
        predictions_[last].validIndex = p.validIndex;
        valid_.pop_back();
        freeIds_.push_back(id);
    }

    // One record per prediction id, so that the model's own bookkeeping costs one cache miss.
    struct Prediction {
        std::uint32_t stamp = 0;      // bumped when the prediction fires or is invalidated
        std::uint32_t validIndex = 0; // index in valid_ while valid
        QueueHandle handle;           // eager invalidation only
    };

    Q queue_;
    Invalidation invalidation_;
    bool eager_;
    Delays delays_;
    std::vector<double> delayTable_;
    Xorshift rng_{kHoldSeed};
    double now_ = 0.0;
    std::vector<Prediction> predictions_;
    std::vector<std::uint32_t> valid_; // ids of valid pending predictions
    std::vector<std::uint32_t> freeIds_;
    std::size_t stalePops_ = 0;
    std::size_t cleanups_ = 0;
};

template <class Q>
void runHolds(benchmark::State& state, Q queue, Invalidation invalidation, Delays delays) {
    const auto bodies = static_cast<std::size_t>(state.range(0));
    HoldModel<Q> model(std::move(queue), invalidation, delays);
    for (std::size_t k = 0; k < bodies * kPredictionsPerBody; ++k)
        model.schedule();
    // Reach the steady state (stale population, time spread) before timing; bins tuned on the
    // way in and again for the steady state, as the engine retunes after measuring.
    model.tune();
    for (std::size_t k = 0; k < 2 * bodies * kPredictionsPerBody; ++k)
        model.hold();
    model.tune();
    const std::size_t stale0 = model.stalePops();
    for (auto _ : state)
        model.hold();
    const double entries = static_cast<double>(model.queue().size());
    const double bytes = static_cast<double>(model.queue().bytesReserved());
    state.counters["B/entry"] = bytes / entries;
    state.counters["B/body"] = bytes / static_cast<double>(bodies);
    state.counters["entries/body"] = entries / static_cast<double>(bodies);
    state.counters["stale/hold"] =
        static_cast<double>(model.stalePops() - stale0) / static_cast<double>(state.iterations());
    state.counters["cleanups"] = static_cast<double>(model.cleanups());
}

struct OwnerEvent {
    double time = 0.0;
    std::int32_t i = -1; // the owner
    std::int32_t j = -1;
};

// One entry per owner; Q is the tree, or the heap with each owner's handle kept.
template <class Q> class OwnerHoldModel {
public:
    explicit OwnerHoldModel(std::size_t owners) : queue_(make(owners)), handle_(owners) {
        for (std::size_t i = 0; i < owners; ++i)
            give(static_cast<std::int32_t>(i), delay());
    }
    void hold() {
        const OwnerEvent e = queue_.top();
        queue_.pop();
        now_ = e.time;
        give(e.i, now_ + delay());
        if (rng_.next() % 3 == 0) {
            const auto n = static_cast<std::int64_t>(handle_.size());
            const std::int64_t j =
                (e.i + static_cast<std::int64_t>(rng_.next() % 601) - 300 + n) % n;
            if (j != e.i) {
                if constexpr (std::is_same_v<Q, BinaryHeapQueue<OwnerEvent>>)
                    queue_.erase(handle_[j]);
                give(static_cast<std::int32_t>(j), now_ + delay());
            }
        }
    }
    const Q& queue() const { return queue_; }

private:
    static Q make(std::size_t owners) {
        if constexpr (std::is_same_v<Q, BinaryHeapQueue<OwnerEvent>>)
            return Q{};
        else
            return Q(static_cast<int>(owners));
    }
    double delay() { return kMeanDelay * -std::log1p(-rng_.uniform()); }
    void give(std::int32_t i, double t) { handle_[i] = queue_.push(OwnerEvent{t, i, -1}); }

    Q queue_;
    std::vector<QueueHandle> handle_;
    Xorshift rng_{kHoldSeed};
    double now_ = 0.0;
};

template <class Q> void runOwnerHolds(benchmark::State& state) {
    const auto owners = static_cast<std::size_t>(state.range(0));
    OwnerHoldModel<Q> model(owners);
    for (std::size_t k = 0; k < 2 * owners; ++k) // the steady spread of times
        model.hold();
    for (auto _ : state)
        model.hold();
    state.counters["B/body"] =
        static_cast<double>(model.queue().bytesReserved()) / static_cast<double>(owners);
}

// Keeps ns per hold by benchmark name so that the ratios can be printed after the run; with
// --benchmark_repetitions the median is kept (robust to other jobs on a shared machine).
class RatioReporter : public benchmark::ConsoleReporter {
public:
    // Colours only on a terminal, so that saved output stays plain text.
    RatioReporter() : ConsoleReporter(isatty(fileno(stdout)) ? OO_ColorTabular : OO_Tabular) {}

    void ReportRuns(const std::vector<Run>& runs) override {
        for (const Run& run : runs) {
            const std::string name = run.run_name.function_name + "/" + run.run_name.args;
            if (run.run_type == Run::RT_Iteration && !medianSeen_.count(name))
                nsPerHold[name] = run.GetAdjustedCPUTime();
            if (run.run_type == Run::RT_Aggregate && run.aggregate_name == "median") {
                nsPerHold[name] = run.GetAdjustedCPUTime();
                medianSeen_.insert(name);
            }
        }
        ConsoleReporter::ReportRuns(runs);
    }
    std::map<std::string, double> nsPerHold;

private:
    std::set<std::string> medianSeen_;
};

// Google Benchmark appends "/<N>" (and run options) to this.
std::string benchmarkName(const char* queue, const char* invalidation, const char* delays) {
    return std::string("hold/") + queue + "/" + invalidation + "/" + delays;
}

void printRatios(const std::map<std::string, double>& ns) {
    const char* queues[] = {"heap", "bpq"};
    const Invalidation modes[] = {Invalidation::None, Invalidation::Lazy, Invalidation::Eager};
    for (const char* delays : {"exponential", "uniform"}) {
        const auto at = [&](const char* q, Invalidation m, std::size_t n) {
            const auto it = ns.find(benchmarkName(q, name(m), delays) + "/" + std::to_string(n));
            return it == ns.end() ? std::nan("") : it->second;
        };
        bool header = false;
        for (const std::size_t n : {512u, 4096u, 32768u, 262144u}) {
            if (std::isnan(at("heap", Invalidation::None, n) + at("bpq", Invalidation::Eager, n)))
                continue; // filtered out of this run
            if (!header) {
                std::printf("\n%s delays: ns per hold (CPU) and ratios (> 1: the second named is "
                            "faster)\n%7s",
                            delays, "N");
                for (const Invalidation m : modes)
                    for (const char* q : queues)
                        std::printf(" %6s-%-5s", q, name(m));
                std::printf(" | heap/bpq: none  lazy eager | eager/lazy: heap   bpq\n");
                header = true;
            }
            std::printf("%7zu", n);
            for (const Invalidation m : modes)
                for (const char* q : queues)
                    std::printf(" %12.1f", at(q, m, n));
            const auto ratio = [&](const char* q1, Invalidation m1, const char* q2,
                                   Invalidation m2) { return at(q1, m1, n) / at(q2, m2, n); };
            std::printf(" |        %5.2f %5.2f %5.2f |        %5.2f %5.2f\n",
                        ratio("heap", Invalidation::None, "bpq", Invalidation::None),
                        ratio("heap", Invalidation::Lazy, "bpq", Invalidation::Lazy),
                        ratio("heap", Invalidation::Eager, "bpq", Invalidation::Eager),
                        ratio("heap", Invalidation::Eager, "heap", Invalidation::Lazy),
                        ratio("bpq", Invalidation::Eager, "bpq", Invalidation::Lazy));
        }
    }
}

constexpr std::size_t kOwnerSizes[] = {512, 32768, 262144, 1000000};

void printOwnerRatios(const std::map<std::string, double>& ns) {
    bool header = false;
    for (const std::size_t n : kOwnerSizes) {
        const auto tree = ns.find("owner/tree/" + std::to_string(n));
        const auto heap = ns.find("owner/heap/" + std::to_string(n));
        if (tree == ns.end() || heap == ns.end()) continue;
        if (!header) {
            std::printf("\nOne entry per owner: ns per hold (CPU)\n%8s %10s %10s %10s\n", "N",
                        "tree", "heap", "tree/heap");
            header = true;
        }
        std::printf("%8zu %10.1f %10.1f %10.2f\n", n, tree->second, heap->second,
                    tree->second / heap->second);
    }
}

void registerAll() {
    for (const std::size_t owners : kOwnerSizes) {
        benchmark::RegisterBenchmark("owner/tree", runOwnerHolds<TournamentQueue<OwnerEvent>>)
            ->Arg(static_cast<std::int64_t>(owners))
            ->Iterations(kTimedHolds)
            ->Unit(benchmark::kNanosecond);
        benchmark::RegisterBenchmark("owner/heap", runOwnerHolds<BinaryHeapQueue<OwnerEvent>>)
            ->Arg(static_cast<std::int64_t>(owners))
            ->Iterations(kTimedHolds)
            ->Unit(benchmark::kNanosecond);
    }
    for (const std::size_t bodies : {512u, 4096u, 32768u, 262144u})
        for (const Delays delays : {Delays::Exponential, Delays::Uniform})
            for (const Invalidation mode :
                 {Invalidation::None, Invalidation::Lazy, Invalidation::Eager}) {
                const char* d = delays == Delays::Exponential ? "exponential" : "uniform";
                const auto reg = [&](const char* q, auto queueMaker) {
                    benchmark::RegisterBenchmark(
                        benchmarkName(q, name(mode), d).c_str(),
                        [=](benchmark::State& s) { runHolds(s, queueMaker(), mode, delays); })
                        ->Arg(static_cast<std::int64_t>(bodies))
                        ->Iterations(kTimedHolds)
                        ->Unit(benchmark::kNanosecond);
                };
                reg("heap", [] { return BinaryHeapQueue<HoldEvent>{}; });
                // Placeholder bins; tune() sets them from the steady-state queue.
                reg("bpq", [] { return BoundedPriorityQueue<HoldEvent>(1.0, 1, 0.0); });
            }
}

} // namespace
} // namespace terrace::dmd

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    terrace::dmd::registerAll();
    terrace::dmd::RatioReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    terrace::dmd::printRatios(reporter.nsPerHold);
    terrace::dmd::printOwnerRatios(reporter.nsPerHold);
    benchmark::Shutdown();
    return 0;
}
