// Question: what does one exact free rotation cost per body kind? Reported as ns per
// freeRotate call (one call per iteration, the state carried along so that successive calls
// visit the whole orbit). The asymmetric top is measured on a generic orbit (theta series), a
// near-separatrix orbit with 1 − m ≈ 1e-6 (Legendre form chosen automatically), and with each
// angle method forced on the generic orbit, and as attitude(t) of an orbit prepared once.
#include "core/asymmetric_top.hpp"
#include "core/linear_rotor.hpp"
#include "core/sphere.hpp"
#include "core/symmetric_top.hpp"
#include <benchmark/benchmark.h>
#include <cmath>

namespace {

using namespace terrace;

constexpr double dt = 0.018; // the paper's SMD step, 1.8 fs, in internal time units

TopState topState(const Vec3& Lbody) {
    TopState s;
    s.A = Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
    s.L = s.A.transpose() * Lbody;
    return s;
}

template <class Kind>
void run(benchmark::State& state, typename Kind::State s, const BodyParams& p) {
    for (auto _ : state) {
        Kind::freeRotate(s, p, dt);
        benchmark::DoNotOptimize(s);
    }
    state.counters["ns_per_call"] =
        benchmark::Counter(static_cast<double>(state.iterations()),
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_Sphere(benchmark::State& state) {
    run<Sphere>(state, {}, {18.0, Vec3::Zero()});
}

void BM_LinearRotor(benchmark::State& state) {
    LinearRotor::State s;
    s.s = Vec3(1.0, 2.0, 0.5).normalized();
    s.w = Vec3(0.3, -0.4, 0.2);
    s.w -= s.w.dot(s.s) * s.s;
    run<LinearRotor>(state, s, {18.0, Vec3(1.154, 1.154, 0.0)});
}

void BM_SymmetricTop(benchmark::State& state) {
    run<SymmetricTop>(state, topState(Vec3(0.7, -1.2, 1.9)), {18.0, Vec3(1.0, 1.0, 2.5)});
}

void asymmetric(benchmark::State& state, const Vec3& Lbody, AsymmetricTop::AngleMethod method) {
    const BodyParams p{18.0, Vec3(1.0, 2.0, 3.0)};
    TopState s = topState(Lbody);
    for (auto _ : state) {
        AsymmetricTop::freeRotate(s, p, dt, method);
        benchmark::DoNotOptimize(s);
    }
    state.counters["ns_per_call"] =
        benchmark::Counter(static_cast<double>(state.iterations()),
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

const Vec3 generic(1.0, -1.0, 1.0);
// L3 chosen so that E2 I2 − L² = −1e-6 L1²(I2 − I1)/I1 for I = (1, 2, 3): 1 − m ≈ 1e-6.
const Vec3 nearSeparatrix(0.8, 1.1, std::sqrt(0.64 * (1.0 + 1e-6) * 3.0));

void BM_AsymmetricTopGeneric(benchmark::State& state) {
    asymmetric(state, generic, AsymmetricTop::AngleMethod::Automatic);
}
void BM_AsymmetricTopThetaSeries(benchmark::State& state) {
    asymmetric(state, generic, AsymmetricTop::AngleMethod::ThetaSeries);
}
void BM_AsymmetricTopLegendrePi(benchmark::State& state) {
    asymmetric(state, generic, AsymmetricTop::AngleMethod::LegendrePi);
}
void BM_AsymmetricTopNearSeparatrix(benchmark::State& state) {
    asymmetric(state, nearSeparatrix, AsymmetricTop::AngleMethod::Automatic);
}

// Many times on one orbit (an event search): the orbit is prepared once outside the loop.
void BM_AsymmetricTopPreparedAttitude(benchmark::State& state) {
    const BodyParams p{18.0, Vec3(1.0, 2.0, 3.0)};
    const AsymmetricTop::FreeRotation flight(topState(generic), p);
    double t = 0.0;
    for (auto _ : state) {
        t += dt;
        benchmark::DoNotOptimize(flight.attitude(t));
    }
    state.counters["ns_per_call"] =
        benchmark::Counter(static_cast<double>(state.iterations()),
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

} // namespace

BENCHMARK(BM_Sphere);
BENCHMARK(BM_LinearRotor);
BENCHMARK(BM_SymmetricTop);
BENCHMARK(BM_AsymmetricTopGeneric);
BENCHMARK(BM_AsymmetricTopThetaSeries);
BENCHMARK(BM_AsymmetricTopLegendrePi);
BENCHMARK(BM_AsymmetricTopNearSeparatrix);
BENCHMARK(BM_AsymmetricTopPreparedAttitude);
BENCHMARK_MAIN();
