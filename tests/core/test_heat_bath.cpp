// The heat bath's parts (core/heat_bath.hpp) and its scene key run.heat_bath: CSVR's propagator
// leaves the canonical distribution of K invariant and relaxes ⟨K⟩ as e^{−t/τ}; Andersen's draw is
// Maxwell–Boltzmann for each body kind; the degrees of freedom; the bath's state round-trips;
// the key's refusals name the key and the cause.
#include "core/heat_bath.hpp"
#include "core/linear_rotor.hpp"
#include "core/sphere.hpp"
#include "core/symmetric_top.hpp"
#include "scene_errors.hpp"
#include <cmath>
#include <gtest/gtest.h>

namespace test_heat_bath {

using namespace terrace;
using scene_tests::errorOf;

namespace {

struct Moments {
    double mean = 0.0, variance = 0.0;
};
Moments moments(const std::vector<double>& x) {
    Moments m;
    for (const double v : x)
        m.mean += v / double(x.size());
    for (const double v : x)
        m.variance += (v - m.mean) * (v - m.mean) / double(x.size());
    return m;
}

} // namespace

TEST(HeatBath, CsvrPropagatorKeepsTheGammaDistribution) {
    // K drawn from Gamma(f/2, kT), propagated once: still Gamma(f/2, kT) (mean and variance to
    // their sampling errors, 2e5 draws: ~0.3 % and ~0.6 % at f = 10).
    const int f = 10;
    const double kT = 2.5, Kbar = 0.5 * f * kT;
    std::mt19937_64 rng(7);
    std::gamma_distribution<double> canonical(0.5 * f, kT);
    std::vector<double> after;
    double reversed = 0.0;
    for (int k = 0; k < 200000; ++k) {
        double sign = 1.0;
        after.push_back(csvrKinetic(canonical(rng), Kbar, f, 0.6, rng, sign));
        reversed += sign < 0.0;
    }
    const Moments m = moments(after);
    EXPECT_NEAR(m.mean, Kbar, 4 * std::sqrt(0.5 * f * kT * kT / 2e5));
    EXPECT_NEAR(m.variance / (0.5 * f * kT * kT), 1.0, 0.03);
    EXPECT_GT(reversed, 0.0); // at c = 0.6 some momenta are reversed, as the exact solution has
}

TEST(HeatBath, CsvrRelaxesTheMeanAsItsEquation) {
    // d⟨K⟩/dt = (K̄ − ⟨K⟩)/τ: from K0, ⟨K(t)⟩ = K̄ + (K0 − K̄) c with c = e^{−t/τ}.
    const int f = 30;
    const double Kbar = 15.0, K0 = 40.0, c = 0.3;
    std::mt19937_64 rng(11);
    std::vector<double> after;
    for (int k = 0; k < 100000; ++k) {
        double sign = 1.0;
        after.push_back(csvrKinetic(K0, Kbar, f, c, rng, sign));
    }
    EXPECT_NEAR(moments(after).mean, Kbar + (K0 - Kbar) * c, 0.05);
    double sign = 1.0;
    EXPECT_DOUBLE_EQ(csvrKinetic(K0, Kbar, f, 1.0, rng, sign), K0); // no time, no change
    EXPECT_EQ(sign, 1.0);
}

TEST(HeatBath, AndersenDrawsMaxwellBoltzmannPerKind) {
    // ⟨K⟩ of one body = (3 + r)/2 kT, whatever it had before (the draw forgets it).
    BodyParams p;
    p.mass = 18.0;
    p.inertia = Vec3(1.154, 1.154, 0.0);
    const double kT = 4.2;
    std::mt19937_64 rng(3);
    auto meanKinetic = [&](auto state, auto kind) {
        using K = decltype(kind);
        double sum = 0.0;
        for (int k = 0; k < 100000; ++k) {
            state.v = Vec3(100.0, 0.0, 0.0);
            andersenCollision<K>(state, p, kT, rng);
            sum += kineticEnergy<K>(state, p);
        }
        return sum / 100000.0 / kT;
    };
    EXPECT_NEAR(meanKinetic(Sphere::State{}, Sphere{}), 1.5, 0.02);
    LinearRotor::State rod;
    rod.s = Vec3(0.0, 0.6, 0.8);
    EXPECT_NEAR(meanKinetic(rod, LinearRotor{}), 2.5, 0.025);
    p.inertia = Vec3(2.0, 2.0, 0.7);
    SymmetricTop::State top;
    top.A = Mat3::Identity();
    top.L = Vec3::Zero();
    EXPECT_NEAR(meanKinetic(top, SymmetricTop{}), 3.0, 0.03);
}

TEST(HeatBath, DegreesOfFreedomFollowMomentum) {
    EXPECT_EQ(heatBathDof(HeatBath::Kind::Andersen, 2 * 100, 100), 500);
    EXPECT_EQ(heatBathDof(HeatBath::Kind::Csvr, 2 * 100, 100), 497);
    EXPECT_EQ(heatBathDof(HeatBath::Kind::None, 3 * 10, 10), 57);
    EXPECT_EQ(heatBathDof(HeatBath::Kind::Csvr, 0, 10), 27);
    // Rods among spheres: 30 rods' two each, the 70 spheres' none.
    EXPECT_EQ(heatBathDof(HeatBath::Kind::Csvr, 2 * 30, 100), 357);
}

TEST(HeatBath, StateRoundTrips) {
    HeatBathState a(42);
    a.rng.discard(17);
    a.removed = -3.25;
    a.clock = 12.5;
    HeatBathState b(1);
    b.restore(nlohmann::json::parse(a.save().dump()));
    EXPECT_EQ(b.rng(), a.rng());
    EXPECT_EQ(b.removed, -3.25);
    EXPECT_EQ(b.clock, 12.5);
    nlohmann::json broken = a.save();
    broken["stream"] = "not a stream";
    EXPECT_THROW(b.restore(broken), SceneError);
}

TEST(HeatBath, SceneKey) {
    const nlohmann::json none = nlohmann::json::object();
    EXPECT_EQ(errorOf(none, {"run.heat_bath=none"}), "");
    EXPECT_EQ(errorOf(none, {R"(run.heat_bath={"kind":"csvr","tau_fs":100})"}), "");
    const Scene s =
        sceneFromJson(none, "t", {R"(run.heat_bath={"kind":"andersen","rate_per_ps":2})"});
    EXPECT_EQ(s.run.heat_bath.kind, "andersen");
    EXPECT_EQ(toJson(s)["run"]["heat_bath"]["rate_per_ps"], 2.0);
    EXPECT_FALSE(
        toJson(sceneFromJson(none, "t", {"run.heat_bath=none"}))["run"].contains("heat_bath"));
    EXPECT_NEAR(heatBathOf(s).rate, 0.2, 1e-15); // per 100 fs
    auto refused = [&](const std::string& set, const std::string& words) {
        const std::string e = errorOf(none, {set});
        EXPECT_NE(e.find(words), std::string::npos) << set << " -> " << e;
    };
    refused(R"(run.heat_bath={"kind":"andersen","rate_per_ps":-1})",
            "run.heat_bath.rate_per_ps: must be > 0, got -1");
    refused(R"(run.heat_bath={"kind":"andersen"})", "run.heat_bath.rate_per_ps: is missing");
    refused(R"(run.heat_bath={"kind":"csvr","rate_per_ps":1})",
            "run.heat_bath.rate_per_ps: is not read by heat_bath.kind csvr");
    refused(R"(run.heat_bath={"kind":"csvr","tau_fs":0.001})", "run.heat_bath.tau_fs: must be >=");
    refused(R"(run.heat_bath={"kind":"cvsr","tau_fs":1})", "did you mean csvr?");
    refused(R"(run.heat_bath={"knd":"csvr"})", "did you mean run.heat_bath.kind?");
    refused("run.heat_bath=andersen", "needs its parameter");
    refused("run.heat_bath=5", "must be \"none\" or an object");
    refused("run.thermostat=csvr", "the kind of heat bath is run.heat_bath");
    refused("run.heat_bth=none", "did you mean run.heat_bath?");
}

} // namespace test_heat_bath
