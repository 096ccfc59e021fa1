// Question: what does it cost DMD to fetch a listed partner's data as N grows, and does the
// layout change it? The engine kept a body's state (96 B for a rod), free orbit (88 B) and book
// (64 B) in three arrays (sys_.bodies, Clocks::orbit_, Schedule::book_) when this was written (a
// rod's orbit is now built from its state, dmd/body_clocks.hpp keepsOrbit); against it, the orbit
// and book side by side beside the states, one 256-byte record per body, records of 3 and 2 cache
// lines (what a compacted partner could be), and one record with a fifth, redundant prefetch.
//
// Why it matters: a collision re-predicts ~29 listed pairs, and each reads its partner's state,
// orbit and book (docs/PERFORMANCE.md, "Where the time goes against N"). At N = 512 these are
// cached; at 10⁶ (0.25 GB of them) each is a miss. On this project's VM a miss waited on costs
// ~370 ns and misses issued together ~21 ns each.
//
// Model: N points placed uniformly at the dense rods' number density (0.0178 Å⁻³, 14.5 listed
// partners within the reach of 5.8 Å), numbered in the Morton order of their cells with the
// engine's own CellList, as Engine::sortBodiesByCell numbers them, so that partners lie as far
// apart in memory as the engine's do. One "event" = a body drawn at random, then every listed
// partner's three parts read (two lines of the state, both ends of the orbit, the book's first
// line), the partner three ahead asked for with prefetches as Prediction::predictBody does, and
// the next event's body and list asked for at the event's start. Between two partners stands
// either nothing (the fetches alone) or a chain of dependent arithmetic of about a held pair's
// prediction, which the prefetches can hide behind as they do in the engine.
//
// Reported per benchmark (arguments N, arithmetic steps per partner): ns per partner (CPU time).
// Run:
//     build/bench/bench_body_layout --benchmark_repetitions=3 --benchmark_report_aggregates_only
#include "dmd/cell_list.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace terrace::dmd {
namespace {

constexpr double kDensity =
    0.0178; // bodies per Å³: the dense rods (66 cells of 5.8 Å a side at 10⁶)
constexpr double kReach = 5.8;   // Å: r_m + skin of the dense rods
constexpr int kAhead = 3;        // partners asked for ahead (the engine's predictBody)
constexpr int kEvents = 1 << 16; // events per iteration

struct StatePart {
    double v[12];
}; // r, v, axis, ω: 96 B
struct OrbitPart {
    double v[11];
}; // axis, ω, |ω|, ω̂ × axis, shift: 88 B
struct alignas(64) BookPart {
    double v[8];
}; // clock, counters, …: 64 B, one line
static_assert(sizeof(StatePart) == 96 && sizeof(OrbitPart) == 88 && sizeof(BookPart) == 64);

struct SplitBodies {
    std::vector<StatePart> state;
    std::vector<OrbitPart> orbit;
    std::vector<BookPart> book;
    explicit SplitBodies(int n) : state(n), orbit(n), book(n) {
        for (int i = 0; i < n; ++i)
            state[i].v[0] = orbit[i].v[0] = book[i].v[0] = i;
    }
    void prefetch(int j) const {
        const char* s = reinterpret_cast<const char*>(&state[j]);
        const char* o = reinterpret_cast<const char*>(&orbit[j]);
        __builtin_prefetch(s);
        __builtin_prefetch(s + sizeof(StatePart) - 1);
        __builtin_prefetch(o);
        __builtin_prefetch(o + sizeof(OrbitPart) - 1);
        __builtin_prefetch(&book[j]);
    }
    double read(int j) const {
        return state[j].v[0] + state[j].v[11] + orbit[j].v[0] + orbit[j].v[10] + book[j].v[0];
    }
};

/// The state in its array, the orbit and book of a body side by side in another (192 B).
struct PairedBodies {
    struct alignas(64) OrbitAndBook {
        OrbitPart orbit;
        BookPart book;
    };
    static_assert(sizeof(OrbitAndBook) == 192);
    std::vector<StatePart> state;
    std::vector<OrbitAndBook> rest;
    explicit PairedBodies(int n) : state(n), rest(n) {
        for (int i = 0; i < n; ++i)
            state[i].v[0] = rest[i].orbit.v[0] = rest[i].book.v[0] = i;
    }
    void prefetch(int j) const {
        const char* s = reinterpret_cast<const char*>(&state[j]);
        const char* o = reinterpret_cast<const char*>(&rest[j]);
        __builtin_prefetch(s);
        __builtin_prefetch(s + sizeof(StatePart) - 1);
        __builtin_prefetch(o);
        __builtin_prefetch(o + 64);
        __builtin_prefetch(o + 128);
    }
    double read(int j) const {
        return state[j].v[0] + state[j].v[11] + rest[j].orbit.v[0] + rest[j].orbit.v[10] +
               rest[j].book.v[0];
    }
};

/// One record of `Lines` cache lines per body, one value read from each line, and `Prefetches`
/// prefetch instructions per body (beyond `Lines`, the extra ones ask again for its last line):
/// the compact layouts a partner could have, and a control for what the count of prefetches
/// alone does.
template <int Lines, int Prefetches> struct LineRecords {
    struct alignas(64) Record {
        double v[8 * Lines];
    };
    std::vector<Record> body;
    explicit LineRecords(int n) : body(n) {
        for (int i = 0; i < n; ++i)
            for (int line = 0; line < Lines; ++line)
                body[i].v[8 * line] = i;
    }
    void prefetch(int j) const {
        const char* b = reinterpret_cast<const char*>(&body[j]);
        for (int k = 0; k < Prefetches; ++k)
            __builtin_prefetch(b + 64 * std::min(k, Lines - 1));
    }
    double read(int j) const {
        double sum = 0.0;
        for (int line = 0; line < Lines; ++line)
            sum += body[j].v[8 * line];
        return sum;
    }
};

/// Every body's partners within kReach (minimum image), the bodies numbered in Morton order.
struct Neighbourhood {
    std::vector<int> first, partners; // partners of i: [first[i], first[i + 1])
    explicit Neighbourhood(int n) {
        const double box = std::cbrt(n / kDensity);
        std::uint64_t s = 0x9e3779b97f4a7c15ULL; // splitmix64 (S. Vigna): fixed, reproducible
        auto uniform = [&s] {
            std::uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
            z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
            z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
            return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1p-53;
        };
        std::vector<Vec3> r(n);
        for (auto& x : r)
            x = Vec3(uniform(), uniform(), uniform()) * box;
        CellList cells(box, kReach, n);
        std::vector<std::pair<std::uint64_t, int>> key(n);
        for (int b = 0; b < n; ++b)
            key[b] = {cells.mortonCode(r[b]), b};
        std::sort(key.begin(), key.end());
        std::vector<Vec3> sorted(n);
        for (int i = 0; i < n; ++i)
            sorted[i] = r[key[i].second];
        for (int i = 0; i < n; ++i)
            cells.insert(i, sorted[i]);
        first.reserve(n + 1);
        for (int i = 0; i < n; ++i) {
            first.push_back(static_cast<int>(partners.size()));
            cells.forEachNeighbourWithin(i, &sorted[i], kReach, [&](int j) {
                if (j == i) return;
                Vec3 d = sorted[i] - sorted[j];
                for (int k = 0; k < 3; ++k)
                    d[k] -= box * std::round(d[k] / box);
                if (d.squaredNorm() <= kReach * kReach) partners.push_back(j);
            });
        }
        first.push_back(static_cast<int>(partners.size()));
    }
};

template <class Bodies> void BM_PartnerFetch(benchmark::State& st) {
    const int n = static_cast<int>(st.range(0));
    const Neighbourhood hood(n);
    const Bodies bodies(n);
    std::vector<int> events(kEvents);
    std::uint64_t s = 0x2545F4914F6CDD1DULL; // xorshift64*: which body each event is about
    for (int& e : events) {
        s ^= s >> 12, s ^= s << 25, s ^= s >> 27;
        e = static_cast<int>((s * 0x2545F4914F6CDD1DULL >> 11) % static_cast<std::uint64_t>(n));
    }
    const int work = static_cast<int>(st.range(1));
    double sum = 0.0, carry = 0.0;
    std::int64_t fetched = 0;
    for (auto _ : st) {
        for (int k = 0; k < kEvents; ++k) {
            // The engine asks for the next event's bodies and list record as this one starts.
            if (k + 2 < kEvents) __builtin_prefetch(&hood.first[events[k + 2]]);
            if (k + 1 < kEvents) {
                bodies.prefetch(events[k + 1]);
                __builtin_prefetch(hood.partners.data() + hood.first[events[k + 1]]);
            }
            const int* p = hood.partners.data() + hood.first[events[k]];
            const int count = hood.first[events[k] + 1] - hood.first[events[k]];
            for (int m = 0; m < std::min(kAhead, count); ++m)
                bodies.prefetch(p[m]);
            for (int m = 0; m < count; ++m) {
                if (m + kAhead < count) bodies.prefetch(p[m + kAhead]);
                // A prediction's arithmetic on what was fetched: `work` steps of four
                // independent chains, started from the previous partner's result, as a
                // prediction (~830 instructions, more than the core's reorder window) follows
                // the one before: no partner's reads start early unless prefetched.
                const double x = bodies.read(p[m]) + carry;
                double a = x, b = 0.5 * x, c = 0.25 * x, d = 0.125 * x;
                for (int w = 0; w < work; ++w) {
                    a = a * 0.999999 + 1e-9;
                    b = b * 0.999999 + 1e-9;
                    c = c * 0.999999 + 1e-9;
                    d = d * 0.999999 + 1e-9;
                }
                carry = 1e-12 * (a + b + c + d);
                sum += carry;
            }
            fetched += count;
        }
    }
    benchmark::DoNotOptimize(sum);
    st.counters["ns_per_partner"] = benchmark::Counter(
        static_cast<double>(fetched), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    st.counters["partners_per_body"] =
        static_cast<double>(hood.partners.size()) / static_cast<double>(n);
}

/// Sizes × the arithmetic per partner: none (the fetches alone) and 100 steps of four chains
/// (~800 instructions, ~140 ns at N = 512: about a held pair's prediction).
void sizes(benchmark::internal::Benchmark* b) {
    for (const long work : {0L, 100L})
        for (const long n : {512L, 4096L, 32768L, 262144L, 1000000L})
            b->Args({n, work});
    b->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_PartnerFetch<SplitBodies>)->Name("three_arrays")->Apply(sizes);
BENCHMARK(BM_PartnerFetch<PairedBodies>)->Name("state_then_orbit_and_book")->Apply(sizes);
BENCHMARK(BM_PartnerFetch<LineRecords<4, 4>>)->Name("one_record")->Apply(sizes);
BENCHMARK(BM_PartnerFetch<LineRecords<4, 5>>)->Name("one_record_5_prefetches")->Apply(sizes);
BENCHMARK(BM_PartnerFetch<LineRecords<3, 3>>)->Name("record_of_3_lines")->Apply(sizes);
BENCHMARK(BM_PartnerFetch<LineRecords<2, 2>>)->Name("record_of_2_lines")->Apply(sizes);

} // namespace
} // namespace terrace::dmd

BENCHMARK_MAIN();
