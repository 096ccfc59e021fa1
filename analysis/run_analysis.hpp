#pragma once
// The analysis of a run, accumulated sample by sample as the run goes (either engine, and
// `terrace analyse` on a trajectory), in memory that does not grow with the run's length
// (DESIGN.md "Analysis"):
//
//   g(r)              rdf_accumulator.hpp: a cell list out to r_max, O(N) per frame, one frame
//                     every `rdfEvery` samples
//   VACF, OACF, MSD   streaming_correlations.hpp: lags 0 … p − 1 by FFT over windows, longer
//                     lags by multiple-tau up to maxLag, following at most `followBodies` bodies
//
// It writes, into the run's directory:
//
//   rdf.csv   r_angstrom,g,err                 centre-of-mass g(r), bins up to r_max (rdf.hpp)
//             [,g_continuous,err_continuous]   a terraced run's g back-converted to the continuous
//                                              model, g·⟨e^{−β(U−V)}⟩ (core/continuous_sums.hpp),
//                                              when the engine filled terracing()
//   vacf.csv  t_ps,c,err                       ⟨v(0)·v(t)⟩/⟨v²⟩ (curves.hpp)
//   oacf.csv  t_ps,c1,c1_err,c2,c2_err         ⟨s(0)·s(t)⟩ and ⟨P₂(s(0)·s(t))⟩
//   msd.csv   t_ps,msd_angstrom2,err           ⟨|r(t) − r(0)|²⟩
//
// A mixture (SpeciesLabels given) adds columns after these, for species A, B, … (named by the
// scene) and each unordered pair of them:
//
//   rdf.csv   g_A_A,err_A_A,g_A_B,err_A_B,…    partial g_ab(r), each by its own pair count
//                                              (rdf_accumulator.hpp): Σ_{a≤b} (P_ab/P) g_ab = g
//   vacf.csv  vacf_A,err_A,…                   each species' ⟨v(0)·v(t)⟩/⟨v²⟩ over its own bodies
//   msd.csv   msd_A,err_A,…                    each species' ⟨|r(t) − r(0)|²⟩, in the unit of the
//                                              msd column
//   oacf.csv  c1_A,c1_err_A,c2_A,c2_err_A,…    rods among spheres only: each species that turns;
//                                              c1 and c2 are then over those species' bodies
//                                              alone (a sphere's axis never moves)
//
// and the summary gives each species' D (diffusion.species) and each pair's g at large r
// (rdf.partials). The species' curves follow their own share of the followed bodies
// (followedPerSpecies: at least one body of every species), each species in correlators of its
// own: a mixture's time correlations hold and cost about twice a plain scene's (the followed
// bodies once for the total, once for their species). A scene of one kind of body writes exactly
// the columns and numbers it wrote before mixtures.
//
// Under the scene's units lj (core/unit_system.hpp) the columns are r_sigma, t_tau and
// msd_sigma2, in σ, τ and σ²; the summary entries stay in real units (the run's summary.json
// converts them in its "reduced" entry).
//
// and returns the summary entries (D by Einstein and Green–Kubo, each with its block error; g at
// large r). err is one standard error from `blocks` block estimates (block_average.hpp).
// oacf.csv is written only when the bodies rotate (some axis changes between samples); for
// spheres, whose axis is a constant placeholder, any stale oacf.csv in the directory is removed,
// and the summary's "oacf" entry says so. The blocks of time origins and of g(r) frames are laid
// out over the planned number of samples, as the reference analysis lays them over the samples
// it is given: a run that reaches its planned length gets the same blocks. A run stopped early is
// analysed over the samples it has, its last blocks short or empty.
#include "analysis/rdf_accumulator.hpp" // and PositionOf
#include "analysis/species_labels.hpp"
#include "core/continuous_sums.hpp"
#include "core/snapshot.hpp"
#include "core/unit_system.hpp"
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <span>
#include <vector>

namespace terrace::analysis {

class StreamingCorrelations;

struct StreamingOptions {
    int blocks = 8;
    double maxLagPs = 0.0;        // 0: half the planned span
    double rdfBinAngstrom = 0.05; // Å
    double rdfMaxAngstrom = 0.0;  // Å, at most L/2; 0: L/2
    int rdfEvery = 1;             // samples between g(r) frames
    int followBodies = 4096;      // bodies the time correlations follow; 0: all
    int lagsPerLevel = 16;        // p of the multiple-tau grid
    double beta = 0.0;            // 1/kT, mol/kJ, for the back-conversion of g(r); 0: none
};

class RunAnalysis {
public:
    /// plannedSamples ≥ 4 (fewer: nothing to analyse, do not build one). `species`: a
    /// mixture's labels (body i's species, i in the order of the samples), empty for one kind.
    RunAnalysis(int bodies, double boxLength, double sampleIntervalPs, long plannedSamples,
                const StreamingOptions& options, const SpeciesLabels& species = {});
    ~RunAnalysis();
    RunAnalysis(const RunAnalysis&) = delete;
    RunAnalysis& operator=(const RunAnalysis&) = delete;

    void add(const Snapshot& sample);
    /// The next sample in parts, so that a large system's sample is never held whole: the
    /// followed bodies alone (followedBodies(), in that order) and, when the sample is a g(r)
    /// frame (wantsPositions()), every body's position, read body by body where it lives
    /// (analysis/rdf_accumulator.hpp PositionOf; else empty). The same numbers as add() of the
    /// whole sample.
    void add(const Snapshot& followed, const PositionOf& positionOf);
    /// The bodies the time correlations follow (indices into a whole sample), in order.
    const std::vector<int>& followedBodies() const;
    /// Whether the next sample is a g(r) frame, which needs every body's position.
    bool wantsPositions() const { return samples_ % options_.rdfEvery == 0; }
    long samples() const { return samples_; }
    /// Where an engine puts its pairs' e^{−β(U−V)} on g(r) frames (g_continuous in rdf.csv); the
    /// bins of g(r). Null without a beta.
    TerracingProfile* terracing() { return terracing_.bins() > 0 ? &terracing_ : nullptr; }
    const TerracingProfile& terracingProfile() const { return terracing_; }
    /// Writes the CSVs into dir (created if needed) and returns the summary entries; needs at
    /// least 4 samples (std::invalid_argument). Everything is computed before anything is written.
    /// The CSVs' r and t columns, and the MSD, in `units`.
    nlohmann::json write(const std::filesystem::path& dir,
                         const UnitSystem& units = UnitSystem::real()) const;
    /// Heap memory held by the accumulators, bytes.
    std::size_t bytes() const;
    /// The accumulators' state as bytes (state_bytes.hpp), for a restart file: independent of
    /// the number of samples taken, and of N beyond the followed bodies and g(r)'s bins.
    std::vector<std::uint8_t> state() const;
    /// Takes a state() into this analysis, built with the same settings: the samples are then
    /// those of the analysis that wrote it, and the next add() goes on from there, to the same
    /// bits. std::invalid_argument when it does not fit (this analysis is then unusable).
    void restore(std::span<const std::uint8_t> state);

private:
    StreamingOptions options_;
    int blocks_, bodies_;
    long planned_, samples_ = 0;
    double dtPs_, boxLength_;
    std::unique_ptr<RdfAccumulator> rdf_;
    std::unique_ptr<StreamingCorrelations> correlations_;
    TerracingProfile terracing_;
    // A mixture's: labels, and per species its time correlations over its followed bodies,
    // which are entries speciesEntries_[a][k] of followedBodies(); a sample's part for them.
    SpeciesLabels species_;
    std::vector<std::unique_ptr<StreamingCorrelations>> speciesCurves_;
    std::vector<std::vector<int>> speciesEntries_;
    Snapshot speciesPart_;
    /// Each species' curves take their followed bodies' entries of `frame`, whose entry for
    /// followed body k is index[k] (k itself when index is null).
    void addSpecies(const Snapshot& frame, const int* index);
};

} // namespace terrace::analysis
