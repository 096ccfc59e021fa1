#pragma once
// Correlation files from independent replicas of one scene (different seeds), with error bars
// from the spread of the replicas instead of blocks of one run:
//
//     value = (1/R) Σ_r c_r(x),   err² = Σ_r (c_r − value)² / (R (R − 1))
//
// (block_average.hpp with one equally weighted block per replica). Each replica's curve uses all
// of its own time origins and frames (correlations.hpp). Replicas are statistically independent
// by construction, so these errors hold at every lag without any assumption about correlation
// times; with R replicas they carry R − 1 degrees of freedom (compare.hpp assumes 7: use R = 8
// for regression checks). The files and columns are those of writeCorrelations.
#include "analysis/correlations.hpp"
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

namespace terrace::analysis {

/// R ≥ 2 replicas, each sampled on the same time grid (interval and length) with the same N and
/// box. Options::blocks only sets the lag limit and the blocking inside each replica.
nlohmann::json writeReplicaCorrelations(const std::vector<std::vector<Snapshot>>& replicas,
                                        const std::filesystem::path& dir,
                                        const Options& options = {});

} // namespace terrace::analysis
