#include "cli/thermo.hpp"
#include "analysis/block_average.hpp"
#include "core/format_text.hpp"
#include "core/pressure.hpp"
#include "core/units.hpp"
#include <cmath>
#include <cstdio>
#include <limits>

namespace terrace::cli {

namespace {

/// The virial (kJ/mol) of sample `now`: SMD's at its instant, DMD's over [before, now].
double virialAt(const SampleRecord& now, const SampleRecord& before, VirialKind kind) {
    if (kind == VirialKind::Instantaneous) return now.virial;
    return impulseVirialOver(before.virial, now.virial, before.time, now.time);
}

} // namespace

PressureTerms pressureTerms(const SampleRecord& now, const SampleRecord& before, VirialKind kind,
                            double volume) {
    return {virialPressure(now.kineticTranslational, 0.0, volume),
            virialPressure(0.0, virialAt(now, before, kind), volume)};
}

nlohmann::json pressureSummary(const analysis::Estimate& all, double kinetic, double virial,
                               long samples, VirialKind kind, double sigma, double epsilon) {
    auto reduced = [&](double x) { return reducedPressure(x, sigma, epsilon); };
    return {{"mean_bar", units::bar(all.mean)},
            {"error_bar", units::bar(all.err)},
            {"mean_reduced", reduced(all.mean)},
            {"error_reduced", reduced(all.err)},
            {"kinetic_term_reduced", reduced(kinetic)},
            {"virial_term_reduced", reduced(virial)},
            {"samples", samples},
            {"blocks", pressureBlocks},
            {"method", kind == VirialKind::Impulse
                           ? "impulse virial over each sample interval, K_trans at its end"
                           : "virial and K_trans at each sample"}};
}

std::string thermoHeader(const ThermoLayout& layout) {
    const bool dmd = layout.kind == VirialKind::Impulse;
    std::string text;
    if (layout.units.reduced())
        text = "time_tau,kinetic_translational_per_body,kinetic_rotational_per_body,"
               "potential_per_body,potential_continuous_per_body,total_per_body,"
               "temperature_reduced,pressure_reduced";
    else
        text = "time_ps,kinetic_translational,kinetic_rotational,potential,"
               "potential_continuous,total,temperature_K,pressure_bar";
    text += dmd ? ",collisions" : "";
    if (layout.heatBath)
        text += layout.units.reduced() ? ",effective_total_per_body" : ",effective_total";
    text += "\n";
    text += layout.units.reduced() ? "# tau,epsilon,epsilon,epsilon,epsilon,epsilon,T*,P*"
                                   : "# ps,kJ/mol,kJ/mol,kJ/mol,kJ/mol,kJ/mol,K,bar";
    text += dmd ? ",count" : "";
    if (layout.heatBath) text += layout.units.reduced() ? ",epsilon" : ",kJ/mol";
    text += "\n";
    if (layout.units.reduced())
        text += "# energies per body of " + std::to_string(layout.bodies) + " in reduced units (" +
                unitScale(layout.units) + "); ";
    else
        text += "# energies of the whole system of " + std::to_string(layout.bodies) + " bodies; ";
    const std::string pressure = layout.units.reduced() ? "pressure_reduced" : "pressure_bar";
    text += dmd ? "potential terraced, potential_continuous the model's continuous U; " + pressure +
                      " and collisions over the interval since the previous row\n"
                : "potential and potential_continuous the model's continuous U; " + pressure +
                      " at the row's instant\n";
    return text;
}

std::string unitScale(const UnitSystem& u) {
    return formatText("sigma = %.17g A, epsilon = %.17g kJ/mol, m = %.17g g/mol, tau = %.17g fs",
                      u.sigma(), u.epsilon(), u.mass(), u.tauFs());
}

std::string thermoRow(const SampleRecord& now, const SampleRecord* before,
                      double potentialContinuous, const ThermoLayout& layout) {
    const bool dmd = layout.kind == VirialKind::Impulse;
    const UnitSystem& u = layout.units;
    const double pressure =
        dmd && !before
            ? std::numeric_limits<double>::quiet_NaN()
            : u.pressure(virialPressure(now.kineticTranslational,
                                        virialAt(now, before ? *before : now, layout.kind),
                                        layout.volume));
    const double temperature = u.temperature(2.0 * now.kinetic / layout.dof);
    // Under real every factor is 1, so the numbers are those written before units existed.
    const double perBody = u.reduced() ? 1.0 / layout.bodies : 1.0;
    auto energy = [&](double e) { return u.energy(e) * perBody; };
    // The time to 15 significant digits, as trajectory.xyz's Time= (core/xyz.cpp): the grid's
    // times are decimals (k · run.sample_fs), and their binary round-off (0.18000000000000002)
    // is not part of them.
    char field[32];
    std::snprintf(field, sizeof field, "%.15g", u.time(now.tPs));
    std::string row = field;
    for (const double x : {energy(now.kineticTranslational),
                           energy(now.kinetic - now.kineticTranslational), energy(now.potential),
                           energy(potentialContinuous), energy(now.total), temperature, pressure}) {
        if (std::isfinite(x))
            std::snprintf(field, sizeof field, "%.17g", x);
        else
            std::snprintf(field, sizeof field, "nan");
        row += "," + std::string(field);
    }
    if (dmd) {
        std::snprintf(field, sizeof field, ",%.0f",
                      before ? now.collisions - before->collisions : 0.0);
        row += field;
    }
    if (layout.heatBath) {
        std::snprintf(field, sizeof field, ",%.17g", energy(now.total + now.bath));
        row += field;
    }
    return row + "\n";
}

} // namespace terrace::cli
