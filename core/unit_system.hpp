#pragma once
// The units a scene's keys are read in and its results written in (the scene key "units",
// docs/UNITS.md). The engines always compute in terrace's own units (core/units.hpp: Å, g/mol,
// kJ/mol, 0.1 ps); a UnitSystem only converts at the edges, so a scene gives the same trajectory
// whichever units it is written in.
//
//   real  Å, g/mol, kJ/mol, K, fs and ps as the keys' names say (every factor 1, so that output
//         is bit for bit what it was before the choice existed)
//   lj    reduced units of the scene's model: σ = potential.sigma, ε = potential.epsilon,
//         m = body.mass, τ = σ·sqrt(m/ε), k_B T in ε. Times in τ, lengths in σ, energies in ε,
//         pressures in ε/σ³, diffusion in σ²/τ, velocities in σ/τ.
//
// state.temperature (T*) and state.density (ρ*) are reduced in both systems, as they always were.
#include "core/units.hpp"
#include <cmath>
#include <limits>
#include <string>

namespace terrace {

/// What a scene key's number measures, in the unit the key's name gives under `real`.
enum class Dimension {
    TimeFs,          // keys ending in _fs
    TimePs,          // keys ending in _ps
    Length,          // Å
    Energy,          // kJ/mol
    Velocity,        // Å/ps (state.particles[].v)
    AngularVelocity, // rad/ps (state.particles[].omega)
};

class UnitSystem {
public:
    /// Terrace's real units: every conversion is the identity.
    static UnitSystem real() { return UnitSystem(); }
    /// Reduced units of a model with length σ (Å), energy ε (kJ/mol) and body mass m (g/mol).
    static UnitSystem lj(double sigma, double epsilon, double mass) {
        UnitSystem u;
        u.reduced_ = true;
        u.sigma_ = sigma;
        u.epsilon_ = epsilon;
        u.mass_ = mass;
        u.tau_ = sigma * std::sqrt(mass / epsilon);
        return u;
    }

    bool reduced() const { return reduced_; }
    const char* name() const { return reduced_ ? "lj" : "real"; }
    double sigma() const { return sigma_; }     // Å
    double epsilon() const { return epsilon_; } // kJ/mol
    double mass() const { return mass_; }       // g/mol
    double tauFs() const { return units::toFs(tau_); }
    double tauPs() const { return units::toPs(tau_); }

    /// How many of the key's real unit one unit of this system is (1 under real).
    double scale(Dimension d) const {
        if (!reduced_) return 1.0;
        switch (d) {
        case Dimension::TimeFs:
            return tauFs();
        case Dimension::TimePs:
            return tauPs();
        case Dimension::Length:
            return sigma_;
        case Dimension::Energy:
            return epsilon_;
        case Dimension::Velocity:
            return sigma_ / tauPs();
        case Dimension::AngularVelocity:
            return 1.0 / tauPs();
        }
        return 1.0;
    }

    /// A key's value as given in this system, in the key's real unit.
    double toReal(double given, Dimension d) const { return given * scale(d); }

    /// The inverse of toReal: where a value came from toReal, the given value exactly (the
    /// quotient, or a neighbour of it a few ulps away), so that a scene written back and read
    /// again gives the same numbers; otherwise the correctly rounded quotient.
    double fromReal(double real, Dimension d) const {
        const double s = scale(d), q = real / s;
        if (q * s == real || !std::isfinite(q)) return q;
        double down = q, up = q;
        for (int k = 0; k < 4; ++k) {
            down = std::nextafter(down, -std::numeric_limits<double>::infinity());
            up = std::nextafter(up, std::numeric_limits<double>::infinity());
            if (down * s == real) return down;
            if (up * s == real) return up;
        }
        return q;
    }

    // Results, from the quantities the runs record in real units.
    // Through fs: sample times are mostly whole fs, and τ often is (100 fs for σ = 1 Å, m = 1
    // g/mol, ε = 1 kJ/mol), where 0.1 ps is not exact in binary.
    double time(double ps) const { return reduced_ ? ps * 1000.0 / tauFs() : ps; }
    double timeOfFs(double fs) const { return reduced_ ? fs / tauFs() : fs / 1000.0; }
    double energy(double kjPerMol) const { return reduced_ ? kjPerMol / epsilon_ : kjPerMol; }
    double length(double angstrom) const { return reduced_ ? angstrom / sigma_ : angstrom; }
    /// The temperature of a thermal energy kT (kJ/mol): K, or T* = kT/ε.
    double temperature(double kT) const { return reduced_ ? kT / epsilon_ : units::kelvin(kT); }
    /// Of a temperature in K.
    double temperatureOfKelvin(double kelvin) const {
        return reduced_ ? kelvin * units::kB / epsilon_ : kelvin;
    }
    /// Of a pressure in kJ/mol/Å³: bar, or P* = Pσ³/ε.
    double pressure(double p) const {
        return reduced_ ? p * sigma_ * sigma_ * sigma_ / epsilon_ : units::bar(p);
    }
    /// Of a diffusion coefficient in Å²/ps.
    double diffusion(double a2PerPs) const {
        return reduced_ ? a2PerPs * tauPs() / (sigma_ * sigma_) : a2PerPs;
    }
    /// Of a rate per ps (collisions, events).
    double rate(double perPs) const { return reduced_ ? perPs * tauFs() / 1000.0 : perPs; }

    // Unit names as people read them, and as column names carry them (ASCII).
    const char* timeUnit() const { return reduced_ ? "τ" : "ps"; }
    const char* timeSuffix() const { return reduced_ ? "tau" : "ps"; }
    const char* lengthSuffix() const { return reduced_ ? "sigma" : "angstrom"; }

private:
    bool reduced_ = false;
    double sigma_ = 1.0, epsilon_ = 1.0, mass_ = 1.0;
    double tau_ = 1.0; // internal time units (core/units.hpp)
};

} // namespace terrace
