#pragma once
// The correlation files of a run, written from its samples (either engine; DESIGN.md "Analysis"):
//
//   rdf.csv   r_angstrom,g,err                 centre-of-mass g(r), bins up to L/2 (rdf.hpp)
//   vacf.csv  t_ps,c,err                       ⟨v(0)·v(t)⟩/⟨v²⟩ (dynamic_correlations.hpp)
//   oacf.csv  t_ps,c1,c1_err,c2,c2_err         ⟨s(0)·s(t)⟩ and ⟨P₂(s(0)·s(t))⟩
//   msd.csv   t_ps,msd_angstrom2,err           ⟨|r(t) − r(0)|²⟩
//
// err is one standard error from `blocks` block estimates (block_average.hpp). Time curves:
// every time origin of the run enters the curve; at each lag the origins that have a partner are
// cut into `blocks` contiguous blocks of about equal size, and the spread of the block curves
// gives the error (dynamic_correlations.hpp). g(r): `blocks` contiguous blocks of frames. Lags run
// to maxLagPs (0: half the sampled span), clipped so that at least two origin blocks reach the
// longest lag.
//
// oacf.csv is written only when the bodies rotate (some axis changes between samples). For
// spheres, whose axis is a constant placeholder, it is not written, any stale oacf.csv in the
// directory is removed, and the summary's "oacf" entry says so.
#include "core/snapshot.hpp"
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

namespace terrace::analysis {

struct Options {
    int blocks = 8;
    double maxLagPs = 0.0; // 0 = half the sampled span
    double rdfBinAngstrom = 0.05;
};

/// Writes the four files into dir (created if needed) and returns a summary: numbers of samples
/// and bodies, sample interval, lag range, diffusion coefficient (Einstein, with error; and
/// Green–Kubo from the VACF over the same lags as a check), g(r) averaged over r ∈ [0.4, 0.5] L.
/// samples: equally spaced in time, same N. Throws std::invalid_argument on unusable samples.
nlohmann::json writeCorrelations(const std::vector<Snapshot>& samples,
                                 const std::filesystem::path& dir, const Options& options = {});

struct RadialDistribution;       // rdf.hpp
struct SampledCurve;             // dynamic_correlations.hpp
struct OrientationalCorrelation; // dynamic_correlations.hpp

namespace detail {
/// Summary entries of a g(r): bins, and g averaged over r ≥ largeRFrom (Å) with a rough error
/// (writeCorrelations: the outer fifth of its range, [0.4, 0.5] L).
nlohmann::json rdfSummary(const RadialDistribution& rdf, double largeRFrom);
/// Writes rdf.csv, vacf.csv, msd.csv and, for rotating bodies, oacf.csv (else removes a stale
/// one) into dir, created if needed: the files of both writeCorrelations and RunAnalysis.
void writeCurveFiles(const std::filesystem::path& dir, const RadialDistribution& rdf,
                     const SampledCurve& vacf, const OrientationalCorrelation* oacf,
                     const SampledCurve& msd);
/// D = (1/3) ∫₀^tmax ⟨v(0)·v(t)⟩ dt (trapezoid rule, truncated at the last lag), Å²/ps, from
/// the normalised VACF on its lag grid (ps) and ⟨v²⟩ in Å² per time unit².
double greenKuboDiffusion(const std::vector<double>& tPs, const std::vector<double>& c,
                          double meanSquareVelocity);
} // namespace detail

} // namespace terrace::analysis
