#pragma once
// A radial pair potential as LAMMPS's `pair_style table linear N` holds it (terrace export
// lammps): N nodes uniform in r² between r_lo and r_hi ("N n RSQ r_lo r_hi" in the table file),
// and between them LAMMPS's linear interpolation in r², which lookup() repeats step by step so
// that the error the table brings to an energy can be measured before LAMMPS runs:
//     k = ⌊(r² − r_lo²)/Δ⌋,   U ≈ e_k + [(r² − r_lo² − kΔ)/Δ] (e_(k+1) − e_k),   Δ = (r_hi² −
//     r_lo²)/(N − 1)
// (LAMMPS's src/pair_table.cpp, compute() with tabstyle LINEAR). With as many internal points as
// the file has and the same range, LAMMPS's nodes are the file's values: its spline through the
// file is evaluated at the file's own abscissae. Values are kept in kJ/mol and kJ/mol/Å; the file
// is written in LAMMPS's real units (kcal/mol, kcal/mol/Å).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace terrace::cli {

/// terrace's energy unit in LAMMPS's real units: 1 kJ/mol = 1/4.184 kcal/mol (thermochemical
/// calorie, the one LAMMPS's real units use).
inline constexpr double kcalPerKj = 1.0 / 4.184;

struct RadialTable {
    std::string key;          // the section's keyword in the table file
    double rLow = 0.0;        // Å, the first node
    double rHigh = 0.0;       // Å, the last node and the pair cutoff
    std::vector<double> u, f; // U and F = −dU/dr at node k, kJ/mol and kJ/mol/Å

    int points() const { return static_cast<int>(u.size()); }
    double spacing() const { return (rHigh * rHigh - rLow * rLow) / (points() - 1); } // Å²
    /// r at node k, as LAMMPS recomputes it from an RSQ table.
    double radius(int k) const {
        return k == points() - 1 ? rHigh : std::sqrt(rLow * rLow + k * spacing());
    }

    /// U at squared distance rsq (kJ/mol), interpolated as LAMMPS does; 0 at and beyond r_hi.
    /// Throws where LAMMPS stops the run: a pair inside r_lo.
    double lookup(double rsq) const {
        if (rsq >= rHigh * rHigh) return 0.0;
        const double inner = rLow * rLow, inverse = 1.0 / spacing();
        if (rsq < inner)
            throw std::domain_error("a pair at " + std::to_string(std::sqrt(rsq)) +
                                    " Å lies inside the table's inner end " + std::to_string(rLow) +
                                    " Å");
        // rsq a few ulp below r_hi² can round onto the last node: its interval is the last one.
        const int k = std::min(static_cast<int>((rsq - inner) * inverse), points() - 2);
        const double fraction = (rsq - (inner + k * spacing())) * inverse;
        return u[k] + fraction * (u[k + 1] - u[k]);
    }
};

/// The table of a radial function `pair(r)` → {U, F = −dU/dr} (kJ/mol, kJ/mol/Å) at n ≥ 2 nodes
/// uniform in r² on [rLow, rHigh].
template <class Pair>
RadialTable tabulate(std::string key, const Pair& pair, double rLow, double rHigh, int n) {
    if (!(n >= 2 && rLow > 0.0 && rHigh > rLow))
        throw std::invalid_argument("a LAMMPS table needs >= 2 points on 0 < r_lo < r_hi");
    RadialTable t{std::move(key), rLow, rHigh, {}, {}};
    t.u.resize(n);
    t.f.resize(n);
    for (int k = 0; k < n; ++k) {
        const auto [u, f] = pair(t.radius(k));
        t.u[k] = u;
        t.f[k] = f;
    }
    return t;
}

/// The table's section of a LAMMPS table file, in kcal/mol and kcal/mol/Å, 17 digits (exact on
/// reading back).
inline std::string tableSection(const RadialTable& t, const std::string& comment) {
    std::string out = "# " + comment + "\n" + t.key + "\n";
    char line[160];
    std::snprintf(line, sizeof line, "N %d RSQ %.17g %.17g\n\n", t.points(), t.rLow, t.rHigh);
    out += line;
    for (int k = 0; k < t.points(); ++k) {
        std::snprintf(line, sizeof line, "%d %.17g %.17g %.17g\n", k + 1, t.radius(k),
                      t.u[k] * kcalPerKj, t.f[k] * kcalPerKj);
        out += line;
    }
    return out + "\n";
}

} // namespace terrace::cli
