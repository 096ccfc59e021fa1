#pragma once
// The pressure and the thermo time series of a run, from its production samples (SampleRecord:
// energies, K_trans, the virial W, the collisions so far).
//
// Pressure per production sample k (core/pressure.hpp), V the box volume:
//   SMD  P_k = (2 K_trans(t_k) + W(t_k)) / (3V), at the instant t_k;
//   DMD  P_k = (2 K_trans(t_k) + [W_imp(t_k) − W_imp(t_{k−1})] / (t_k − t_{k−1})) / (3V), over the
//        sample interval that ends at t_k; the sample at production's start ends none and is left
//        out.
// summary.json "pressure" holds their mean in bar and reduced (P* = Pσ³/ε), one standard error
// from pressureBlocks contiguous blocks of samples (analysis/block_average.hpp), and the mean's
// kinetic and virial terms, accumulated sample by sample (cli/sample_statistics.hpp).
//
// thermo.csv: a row at production's start and every output.thermo_every_fs after it, so a run
// that goes to its end has ⌊run.time_ps / thermo_every_fs⌋ + 1 rows. Its first line names the
// columns (no '#', as in the other CSVs), then comment lines starting with '#' give the units and
// say how the columns are taken, so that pandas (read_csv(..., comment='#')), numpy
// (genfromtxt(..., delimiter=',', names=True)) and gnuplot (set datafile separator comma) read it:
//   time_ps                 production time
//   kinetic_translational   ½ m Σ v², kJ/mol, the whole system's (as every energy column)
//   kinetic_rotational      K − K_trans
//   potential               the engine's own U: DMD the terraced one, SMD the continuous one
//   potential_continuous    the continuous U (SMD: the same as potential)
//   total                   K + the engine's own U (DMD: conserved to round-off)
//   temperature_K           2K / (dof k_B), dof = 3N + R − 3 (R: the bodies' rotational dof)
//   pressure_bar            SMD: at the row's instant; DMD: over the interval since the previous
//                           row (impulse virial difference), nan on the first row
//   collisions              DMD only: collisions (up, down, reflect) since the previous row, 0 on
//                           the first
//   effective_total         with run.heat_bath only: total + the kinetic energy the bath removed
//                           since the run began, which the thermostatted dynamics conserves
// Numbers are written with 17 significant digits (exact on reading back), but for the time: 15,
// which shows a time on the sample grid as the decimal it is (0.18, not 0.18000000000000002).
//
// Under the scene's units lj (core/unit_system.hpp) the columns are time_tau, the energies per
// body in ε with the suffix _per_body (as LAMMPS normalises thermo energies under its lj units),
// temperature_reduced T* and pressure_reduced P*; the comment line names those units.
#include "analysis/block_average.hpp"
#include "cli/restart.hpp"
#include "core/pressure.hpp"
#include "core/unit_system.hpp"
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace terrace::cli {

/// What SampleRecord::virial holds (core/pressure.hpp).
using terrace::VirialKind;

/// Blocks behind the pressure's error (as analysis::StreamingOptions' default for the
/// correlations).
inline constexpr int pressureBlocks = 8;

/// The two terms of P_k in kJ/mol/Å³ at sample `now`, `before` the sample before it (DMD: the
/// interval's start; SMD: unused): kinetic 2K_trans/(3V) and virial W/(3V).
struct PressureTerms {
    double kinetic = 0.0, virial = 0.0;
};
PressureTerms pressureTerms(const SampleRecord& now, const SampleRecord& before, VirialKind kind,
                            double volume);

/// summary.json's "pressure": mean_bar, error_bar, mean_reduced, error_reduced, samples, blocks,
/// kinetic_term_reduced, virial_term_reduced, method, from the mean of P_k and its block error
/// (`total`), the two terms' means and the number of samples behind them. σ in Å, ε in kJ/mol.
/// Errors are null (NaN) when fewer than two blocks hold samples.
nlohmann::json pressureSummary(const analysis::Estimate& total, double kineticMean,
                               double virialMean, long samples, VirialKind kind, double sigma,
                               double epsilon);

struct ThermoLayout {
    VirialKind kind = VirialKind::Instantaneous;
    double volume = 0.0; // Å³
    int dof = 0;         // degrees of freedom of the temperature
    int bodies = 0;
    UnitSystem units;      // of the columns
    bool heatBath = false; // run.heat_bath set: the effective energy's column last
};

/// The scale of reduced units in one line of ASCII (σ, ε, m, τ with 17 digits), for comments.
std::string unitScale(const UnitSystem& u);

/// thermo.csv's header: the column names, then its comment lines.
std::string thermoHeader(const ThermoLayout& layout);

/// The row of sample `now`; `before` is the previous row's sample (nullptr for the first row);
/// `potentialContinuous` the continuous U at `now` (kJ/mol).
std::string thermoRow(const SampleRecord& now, const SampleRecord* before,
                      double potentialContinuous, const ThermoLayout& layout);

} // namespace terrace::cli
