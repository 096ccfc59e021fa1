#pragma once
// One table row from the summary.json files of R replica runs of one setting (cli/run_driver.hpp
// writes them): for each quantity the replica mean and its standard error sqrt(var/R).
//
//   cpu_s_per_ps       CPU seconds per simulated ps (production only; the paper's cost measure)
//   collisions_per_ps  DMD transmissions up + down + reflections per ps (0 for SMD)
//   events_per_ps      all DMD events per ps, virtual, cell and sample events included (0 for SMD)
//   energy_rel_fluct   std(E_total)/|mean U| (the paper's energy measure)
//   energy_drift_per_ps  slope of E_total, kJ/mol per ps
//   temperature_K      mean instantaneous temperature over production
// Efficiency ratios between rows are ratios of cpu_s_per_ps; they are formed by the scripts.
#include <filesystem>
#include <string>
#include <vector>

namespace terrace::experiments {

/// The CSV header of rows written by summaryRow (label first).
std::string summaryHeader();

/// A CSV row "label,engine,runs,simulated_ps,<mean>,<err>,…" over the runs in `dirs` (each holding
/// summary.json). Throws std::runtime_error naming a directory without a usable summary.
std::string summaryRow(const std::string& label, const std::vector<std::filesystem::path>& dirs);

/// Values of dotted keys (e.g. "energy.rel_fluct") of a JSON file, comma separated; a missing key
/// or a non-number gives "nan", a boolean 1 or 0.
std::string jsonValues(const std::filesystem::path& file, const std::vector<std::string>& keys);

/// How replicaValue scales a summary key: as it is, per body (÷ n_bodies), or as a magnitude per
/// N kT (|x| ÷ (n_bodies · k_B · temperature_target_K), kT in kJ/mol: an energy rate's share of the
/// thermal energy).
enum class SummaryScale { total, perBody, magnitudePerNkT };

/// Parses "total", "per-body" or "abs-per-nkt"; throws std::invalid_argument otherwise.
SummaryScale summaryScale(const std::string& name);

/// A dotted key of DIR/summary.json, scaled; NaN where the key is missing or not a number.
double replicaValue(const std::filesystem::path& dir, const std::string& key, SummaryScale scale);

} // namespace terrace::experiments
