#pragma once
// Pressure of rigid bodies in a periodic box from the molecular virial (M. P. Allen and
// D. J. Tildesley, Computer Simulation of Liquids (1987), sec. 2.4):
//
//     P = (2 K_trans + W) / (3V),   W = Σ_{i<j} r_ij·F_ij,
//
// with r_ij the minimum-image separation of the centres of mass and F_ij the whole force of j on
// i; only the translational kinetic energy K_trans = ½ m Σ v_i² enters (torques do no work on the
// centres). SMD has W at every instant. DMD's forces are impulses: over [t0, t1] the time-averaged
// virial is the sum of r_ij·Δp_i over the collisions in it (transmissions and reflections) divided
// by t1 − t0 (B. J. Alder and T. E. Wainwright, J. Chem. Phys. 33, 1439 (1960)), which the DMD
// engine keeps as a running sum W_imp, so that
//
//     P[t0, t1] = (2 K_trans + (W_imp(t1) − W_imp(t0)) / (t1 − t0)) / (3V).
//
// Units: kJ/mol, Å³, the time unit (100 fs) for W_imp's time factor; pressure in kJ/mol/Å³
// (units::bar converts), or reduced, P* = Pσ³/ε.

namespace terrace {

/// What an engine's virial() holds: SMD's W = Σ r_ij·F_ij at the instant (kJ/mol), or DMD's
/// running impulse virial W_imp = Σ r_ij·Δp_i since the run began (kJ/mol × time unit), whose
/// increase over an interval divided by its length is that interval's mean W.
enum class VirialKind { Instantaneous, Impulse };

/// P = (2 K_trans + W)/(3V) in kJ/mol/Å³, from K_trans and W in kJ/mol and V in Å³.
inline constexpr double virialPressure(double kineticTranslational, double virial, double volume) {
    return (2.0 * kineticTranslational + virial) / (3.0 * volume);
}

/// The time-averaged virial (kJ/mol) over [t0, t1] from the running impulse virial (kJ/mol times
/// the time unit) at both ends; t in time units.
inline constexpr double impulseVirialOver(double wImp0, double wImp1, double t0, double t1) {
    return (wImp1 - wImp0) / (t1 - t0);
}

/// P* = Pσ³/ε, from P in kJ/mol/Å³, σ in Å and ε in kJ/mol.
inline constexpr double reducedPressure(double pressure, double sigma, double epsilon) {
    return pressure * sigma * sigma * sigma / epsilon;
}

} // namespace terrace
