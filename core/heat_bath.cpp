#include "core/heat_bath.hpp"
#include "core/units.hpp"
#include <cmath>
#include <sstream>

namespace terrace {

HeatBath heatBathOf(const Scene& scene) {
    HeatBath b;
    const auto& h = scene.run.heat_bath;
    b.kT = scene.kT();
    if (h.kind == "andersen") {
        b.kind = HeatBath::Kind::Andersen;
        b.rate = h.rate_per_ps * units::psPerTimeUnit; // per ps -> per time unit
    } else if (h.kind == "csvr") {
        b.kind = HeatBath::Kind::Csvr;
        b.tau = units::fromFs(h.tau_fs);
    }
    return b;
}

int heatBathDof(HeatBath::Kind kind, int rotationalDofs, int n) {
    const int all = 3 * n + rotationalDofs;
    return kind == HeatBath::Kind::Andersen ? all : all - 3;
}

double csvrKinetic(double K, double Kbar, int f, double c, std::mt19937_64& rng, double& sign) {
    std::normal_distribution<double> gauss(0.0, 1.0);
    const double r1 = gauss(rng);
    // Σ_{i=2}^{f} R_i² is χ² with f − 1 degrees of freedom, i.e. 2·Gamma((f − 1)/2, 1).
    double rest = 0.0;
    if (f > 1) {
        std::gamma_distribution<double> gamma(0.5 * (f - 1), 1.0);
        rest = 2.0 * gamma(rng);
    }
    const double kPerDof = Kbar / f;
    const double next = c * K + (1.0 - c) * kPerDof * (r1 * r1 + rest) +
                        2.0 * r1 * std::sqrt(c * (1.0 - c) * K * kPerDof);
    sign = (K > 0.0 && c < 1.0 && r1 + std::sqrt(c * K / ((1.0 - c) * kPerDof)) < 0.0) ? -1.0 : 1.0;
    return next;
}

HeatBathState::HeatBathState(std::uint64_t seed) : rng(namedStream(seed, "heat bath")) {}

nlohmann::json HeatBathState::save() const {
    std::ostringstream text;
    text << rng;
    return {{"stream", text.str()}, {"removed", removed}, {"clock", clock}};
}

void HeatBathState::restore(const nlohmann::json& j) {
    try {
        std::istringstream text(j.at("stream").get<std::string>());
        text >> rng;
        if (text.fail()) throw SceneError("restart: the heat bath's stream does not read");
        removed = j.at("removed").get<double>();
        clock = j.at("clock").get<double>();
    } catch (const nlohmann::json::exception& e) {
        throw SceneError(std::string("restart: the heat bath's state does not read (") + e.what() +
                         ")");
    }
    if (!std::isfinite(removed) || !(clock >= 0.0))
        throw SceneError("restart: the heat bath's energy or clock is not finite");
}

double exponentialWait(double rate, std::mt19937_64& rng) {
    std::exponential_distribution<double> wait(rate);
    return wait(rng);
}

} // namespace terrace
