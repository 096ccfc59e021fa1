#pragma once
// Units of terrace (DESIGN.md "Units"): length Å, mass g/mol, energy kJ/mol, temperature K.
// The derived time unit is Å·sqrt((g/mol)/(kJ/mol)) = 1e-10 m / sqrt(1e3 J / 1e-3 kg) = 1e-13 s
// = 0.1 ps = 100 fs. Every time inside the engines is in this unit; people see fs or ps.

namespace terrace::units {

/// Boltzmann's constant in kJ/(mol K) (CODATA 2018: R = 8.314462618 J/(mol K)).
inline constexpr double kB = 0.0083144626;

/// Length of the internal time unit in fs and ps.
inline constexpr double fsPerTimeUnit = 100.0;
inline constexpr double psPerTimeUnit = 0.1;

inline constexpr double fromFs(double fs) {
    return fs / fsPerTimeUnit;
}
inline constexpr double fromPs(double ps) {
    return ps / psPerTimeUnit;
}
inline constexpr double toFs(double t) {
    return t * fsPerTimeUnit;
}
inline constexpr double toPs(double t) {
    return t * psPerTimeUnit;
}

/// Temperature in K of a thermal energy kT in kJ/mol.
inline constexpr double kelvin(double kT) {
    return kT / kB;
}

/// The pressure unit, kJ/mol/Å³, in bar: 1e3 J / N_A / 1e-30 m³ / 1e5 Pa, with the exact
/// Avogadro constant N_A = 6.02214076e23 /mol (SI 2019): 1e28 / N_A = 16605.39067173847 bar.
inline constexpr double barPerKjPerMolPerA3 = 1e28 / 6.02214076e23;

/// Pressure in bar of one in kJ/mol/Å³.
inline constexpr double bar(double p) {
    return p * barPerKjPerMolPerA3;
}

} // namespace terrace::units
