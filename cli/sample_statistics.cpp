#include "cli/sample_statistics.hpp"
#include "cli/thermo.hpp"
#include "core/format_text.hpp"
#include "core/units.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace terrace::cli {

namespace {

/// Total energy that wanders by more than this fraction of the kinetic energy is no longer a
/// conserving integration (a healthy SMD run at 1.8 fs stays below 1e-3 of it).
constexpr double energyWanderWarning = 0.01;

nlohmann::json orNull(double x) {
    return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json();
}

/// Blocks over the g(r) frames: at most pressureBlocks, one frame each when fewer are planned.
int frameBlocks(long frames) {
    return int(std::clamp<long>(frames, 1, pressureBlocks));
}

} // namespace

SampleStatistics::SampleStatistics(const SamplePlan& plan)
    : plan_(plan), kinetic_(plan.samples, pressureBlocks), potential_(plan.samples, pressureBlocks),
      pressure_(std::max(0L, plan.samples - (plan.virialKind == VirialKind::Impulse ? 1 : 0)),
                pressureBlocks),
      collisions_(std::max(0L, plan.samples - 1), pressureBlocks),
      continuousU_(plan.frames, frameBlocks(plan.frames)),
      continuousP_(plan.frames, frameBlocks(plan.frames)),
      kineticShiftedSquares_(plan.samples, pressureBlocks) {}

void SampleStatistics::add(const SampleRecord& e) {
    // Refused before anything is added: every accumulator keeps the same samples.
    if (count() >= plan_.samples)
        throw std::out_of_range("sample statistics: more than the " +
                                std::to_string(plan_.samples) + " samples planned");
    const bool first = count() == 0;
    energy_.add(e.tPs, e.total, e.potential); // refuses a time that does not follow, first
    effective_.add(e.tPs, e.total + e.bath, e.potential);
    kinetic_.add(e.kinetic);
    const double shifted = e.kinetic - analysis::canonicalKineticMean(plan_.dof, plan_.kT);
    kineticShiftedSquares_.add(shifted * shifted);
    if (first) firstBath_ = e.bath;
    potential_.add(e.potential);
    // The pressure's two terms (cli/thermo.hpp): DMD's first sample ends no interval.
    if (plan_.virialKind == VirialKind::Instantaneous || !first) {
        const PressureTerms p =
            pressureTerms(e, first ? e : previous_, plan_.virialKind, plan_.volume);
        pressure_.add(p.kinetic + p.virial);
        pressureKinetic_ += p.kinetic, pressureVirial_ += p.virial;
    }
    if (!first) collisions_.add(e.collisions - previous_.collisions);
    if (std::isfinite(e.continuousPotential)) { // a g(r) frame
        continuousU_.add(e.continuousPotential);
        continuousP_.add(virialPressure(e.kineticTranslational, e.continuousVirial, plan_.volume));
    }
    previous_ = e;
}

void SampleStatistics::summarise(nlohmann::json& summary, double sigma, double epsilon) const {
    summary["configurational"] = configurational(sigma, epsilon);
    if (count() == 0) return;
    const analysis::EnergyStats es = energy_.stats();
    const analysis::Estimate k = kinetic_.estimate(), u = potential_.estimate();
    const double dof = plan_.dof;
    summary["temperature_K"] = units::kelvin(2.0 * k.mean / dof);
    // One standard error of each mean from the 8 blocks, for regression checks; null with fewer
    // than two samples.
    summary["temperature_err_K"] = orNull(units::kelvin(2.0 * k.err / dof));
    summary["energy"] = {
        {"initial", es.initial},
        {"final", es.final},
        {"mean", es.mean},
        {"std", es.std},
        {"max_abs_dev", es.maxAbsDev},
        {"rel_fluct", es.relFluct},
        // The paper's "relative fluctuations of the total energy to the potential
        // energy", read as the ratio of the two standard deviations.
        {"fluct_ratio_to_U", es.potentialStd > 0.0 ? es.std / es.potentialStd : 0.0},
        {"drift_per_ps", es.driftPerPs},
        {"units", "kJ/mol"}};
    summary["potential_energy_mean"] = es.potentialMean;
    summary["potential_energy_std"] = es.potentialStd;
    summary["potential_energy_err"] = orNull(u.err);
    summary["pressure"] =
        pressure_.count() == 0
            ? nlohmann::json{{"samples", 0}}
            : pressureSummary(pressure_.estimate(), pressureKinetic_ / double(pressure_.count()),
                              pressureVirial_ / double(pressure_.count()), pressure_.count(),
                              plan_.virialKind, sigma, epsilon);
    // The conserved energy wanders only by the integration's error: H under NVE; under a heat
    // bath H + the energy the bath removed, whose draws turn that error from a fluctuation of H
    // into a drift (cli/heat_bath_summary.hpp).
    const analysis::EnergyStats conserved = plan_.heatBath ? effective_.stats() : es;
    if (conserved.maxAbsDev > energyWanderWarning * k.mean) {
        const std::string text = formatText(
            plan_.heatBath
                ? "effective energy (H + the energy the heat bath removed) wandered by "
                  "%.3g kJ/mol, %.2g%% of the kinetic energy: the integration's error at "
                  "this time step, which the bath's draws turn from a fluctuation of H "
                  "into a drift"
                : "total energy wandered by %.3g kJ/mol, %.2g%% of the kinetic energy: "
                  "the integration does not conserve energy at this time step",
            conserved.maxAbsDev, 100.0 * conserved.maxAbsDev / k.mean);
        summary["warnings"].push_back(text);
        std::fprintf(stderr, "terrace: warning: %s\n", text.c_str());
    }
}

/// The configurational estimators (core/continuous_sums.hpp): the continuous model's ⟨U⟩ and its
/// virial pressure P = (2 K_trans + W)/(3V) on the g(r) frames' configurations, each with a block
/// error. For SMD they are its own U and P on fewer samples; for DMD they remove the terracing of
/// the observable, leaving that of the distribution.
nlohmann::json SampleStatistics::configurational(double sigma, double epsilon) const {
    nlohmann::json j{{"frames", continuousU_.count()}};
    if (continuousU_.count() < 2) return j;
    const analysis::Estimate um = continuousU_.estimate(), pm = continuousP_.estimate();
    j["blocks"] = um.samples; // those holding frames
    j["potential_energy_mean"] = um.mean;
    j["potential_energy_err"] = orNull(um.err);
    // A step table has no configurational virial (its W is NaN): its pressure is the engine's.
    j["pressure_bar"] = orNull(units::bar(pm.mean));
    j["pressure_err_bar"] = orNull(units::bar(pm.err));
    j["pressure_reduced"] = orNull(reducedPressure(pm.mean, sigma, epsilon));
    j["pressure_err_reduced"] = orNull(reducedPressure(pm.err, sigma, epsilon));
    j["method"] = "continuous U and W = sum r_ij.F_ij on the configurations of the g(r) frames";
    return j;
}

nlohmann::json SampleStatistics::collisionRateError(double sampleIntervalPs) const {
    if (count() < 3) return nullptr;
    return orNull(collisions_.estimate().err / sampleIntervalPs);
}

std::vector<std::uint8_t> SampleStatistics::state() const {
    analysis::StateWriter out;
    energy_.write(out);
    for (const auto* b :
         {&kinetic_, &potential_, &pressure_, &collisions_, &continuousU_, &continuousP_})
        b->write(out);
    out.value(pressureKinetic_), out.value(pressureVirial_);
    effective_.write(out);
    kineticShiftedSquares_.write(out);
    out.value(firstBath_);
    out.value(previous_);
    return out.take();
}

void SampleStatistics::restore(std::span<const std::uint8_t> bytes) {
    analysis::StateReader in(bytes);
    energy_.read(in);
    kinetic_.read(in, "temperature blocks");
    potential_.read(in, "potential energy blocks");
    pressure_.read(in, "pressure blocks");
    collisions_.read(in, "collision blocks");
    continuousU_.read(in, "configurational energy blocks");
    continuousP_.read(in, "configurational pressure blocks");
    pressureKinetic_ = in.value<double>("pressure sums");
    pressureVirial_ = in.value<double>("pressure sums");
    effective_.read(in);
    kineticShiftedSquares_.read(in, "kinetic energy's square blocks");
    firstBath_ = in.value<double>("the heat bath's first energy");
    previous_ = in.value<SampleRecord>("the last sample");
    in.finish();
    // Every accumulator saw the same samples.
    const long n = count();
    const long withPressure = n - (plan_.virialKind == VirialKind::Impulse && n > 0 ? 1 : 0);
    if (kinetic_.count() != n || potential_.count() != n || pressure_.count() != withPressure ||
        effective_.count() != n || kineticShiftedSquares_.count() != n ||
        collisions_.count() != std::max(0L, n - 1) || continuousP_.count() != continuousU_.count())
        throw std::invalid_argument("analysis state: the sample statistics disagree on the "
                                    "number of samples (damaged)");
}

} // namespace terrace::cli
