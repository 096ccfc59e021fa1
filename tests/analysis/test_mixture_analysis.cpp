// A mixture's analysis: partial g(r)s counted pair by pair of species (against every pair, by
// brute force), adding up to the total with the weights of their pair counts; an ideal mixture's
// partials are 1; each species' MSD and VACF of bodies in free flight at the species' own speed;
// the state a restart file keeps; and a scene of one kind of body writes the columns it always
// did.
#include "analysis/csv.hpp"
#include "analysis/rdf_accumulator.hpp"
#include "analysis/run_analysis.hpp"
#include "analysis/streaming_correlations.hpp"
#include "core/box.hpp"
#include "core/output_file.hpp"
#include "core/units.hpp"
#include "synthetic_samples.hpp"
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <unistd.h>

namespace test_mixture_analysis {

using namespace terrace;
using namespace terrace::analysis;
namespace fs = std::filesystem;

namespace {

/// g and Σ (P_ab/P) g_ab are one sum of the same integer counts divided in two ways: equal to
/// a few ulps of g.
constexpr double sumRoundOff = 1e-12;
/// A partial's counts recovered from g_ab (g · frames · P_ab · shell / V) are integers, up to the
/// round-off of that product.
constexpr double countRoundOff = 1e-7;
/// An ideal mixture's g_ab within this many of its block errors in every bin with enough pairs
/// (8 blocks: Student's t with 7 degrees of freedom, P(|t| > 6) ≈ 5e-4 a bin).
constexpr double idealSigmas = 6.0;
/// The mean of ((g_ab − 1)/err)² over the bins: 7/5 for t₇ deviations; far above if the errors
/// were too small, far below if too large.
constexpr double zSquaredLow = 0.5, zSquaredHigh = 2.5;
/// Free flight: MSD = v² t² and VACF = 1 exactly, up to the round-off of the FFT sums.
constexpr double freeFlightRelative = 1e-9;

/// Body i's species, dealt at random in the counts given.
std::vector<std::int32_t> dealt(const std::vector<int>& counts, std::uint64_t seed) {
    std::vector<std::int32_t> species;
    for (std::size_t a = 0; a < counts.size(); ++a)
        species.insert(species.end(), std::size_t(counts[a]), std::int32_t(a));
    std::mt19937_64 rng(seed);
    std::shuffle(species.begin(), species.end(), rng);
    return species;
}

SpeciesLabels labels(const std::vector<int>& counts, std::uint64_t seed = 3) {
    SpeciesLabels l;
    for (std::size_t a = 0; a < counts.size(); ++a)
        l.names.push_back(std::string(1, char('A' + a)));
    l.ofBody = dealt(counts, seed);
    return l;
}

/// Frames of uniformly random (unwrapped) positions: an ideal mixture, whatever the species.
std::vector<Snapshot> randomFrames(int frames, int bodies, double length, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uniform(-length, 2.0 * length);
    auto samples = synthetic::emptySamples(frames, bodies, 0.1, length);
    for (auto& f : samples)
        for (auto& r : f.position)
            r = {uniform(rng), uniform(rng), uniform(rng)};
    return samples;
}

double shellVolume(double lo, double hi) {
    return 4.0 / 3.0 * std::numbers::pi * (hi * hi * hi - lo * lo * lo);
}

/// Every pair of every frame, by minimum image: counts[pair of species][bin] below r_max.
std::vector<std::vector<double>> bruteForceCounts(const std::vector<Snapshot>& frames,
                                                  const SpeciesLabels& l, double bin, int bins) {
    const int s = l.count();
    std::vector<std::vector<double>> counts(std::size_t(s * (s + 1) / 2),
                                            std::vector<double>(bins, 0.0));
    const double rMax = bin * bins;
    for (const auto& f : frames) {
        const PeriodicBox box{f.boxLength};
        for (int i = 0; i < f.size(); ++i)
            for (int j = i + 1; j < f.size(); ++j) {
                const double r = box.minimumImage(f.position[i] - f.position[j]).norm();
                if (r >= rMax) continue;
                const int k = static_cast<int>(r / bin);
                if (k < bins) ++counts[speciesPairIndex(l.ofBody[i], l.ofBody[j], s)][k];
            }
    }
    return counts;
}

/// An empty scratch directory of this process, removed at the end of the test.
struct ScratchDirectory {
    fs::path path;
    explicit ScratchDirectory(const std::string& name)
        : path(fs::temp_directory_path() /
               ("terrace_mixture_" + name + "_" + std::to_string(::getpid()))) {
        fs::remove_all(path);
    }
    ~ScratchDirectory() { fs::remove_all(path); }
};

} // namespace

// g = Σ_{a≤b} (P_ab / P) g_ab bin by bin, P_ab = N_a(N_a − 1)/2 or N_a N_b and P = N(N − 1)/2
// (rdf.hpp's N(N − 1)/2 convention), for 2 and 3 species, through the cell list (r_max = L/4)
// and over all pairs (r_max = L/2); and each partial holds exactly the pairs of its species, as
// every pair counted by brute force says (a mix-up of AA and BB would still sum to the total).
TEST(MixtureRdf, PartialsAddUpToTheTotalWithThePairCountsAsWeights) {
    const int n = 90, frames = 24, blocks = 4;
    const double length = 14.0, bin = 0.2;
    const auto samples = randomFrames(frames, n, length, 17);
    for (const std::vector<int>& counts :
         {std::vector<int>{60, 30}, std::vector<int>{1, 80, 9}, std::vector<int>{30, 30, 30}})
        for (const double rMax : {0.25 * length, 0.5 * length}) {
            const SpeciesLabels l = labels(counts);
            RdfAccumulator acc(n, length, bin, rMax, frames, blocks, l);
            for (const auto& f : samples)
                acc.add(f);
            const RadialDistribution total = acc.result();
            const int s = l.count(), bins = static_cast<int>(total.g.size());
            const double all = 0.5 * n * (n - 1.0);
            double pairs = 0.0;
            std::vector<RadialDistribution> partial;
            std::vector<double> weight;
            for (int a = 0; a < s; ++a)
                for (int b = a; b < s; ++b) {
                    partial.push_back(acc.partial(a, b));
                    weight.push_back(acc.pairs(a, b));
                    pairs += acc.pairs(a, b);
                    EXPECT_EQ(acc.pairs(a, b), acc.pairs(b, a));
                }
            ASSERT_EQ(pairs, all);
            const auto brute = bruteForceCounts(samples, l, bin, bins);
            const std::string where = std::to_string(s) + " species, r_max " + std::to_string(rMax);
            for (int k = 0; k < bins; ++k) {
                double sum = 0.0;
                for (std::size_t p = 0; p < partial.size(); ++p) {
                    if (weight[p] == 0.0) { // a species of one body: no like pairs
                        EXPECT_TRUE(std::isnan(partial[p].g[k])) << where;
                        EXPECT_EQ(brute[p][k], 0.0);
                        continue;
                    }
                    sum += weight[p] / all * partial[p].g[k];
                    const double ideal = frames * weight[p] * shellVolume(k * bin, (k + 1) * bin) /
                                         std::pow(length, 3);
                    EXPECT_NEAR(partial[p].g[k] * ideal, brute[p][k], countRoundOff)
                        << where << ", pair " << p << ", bin " << k;
                }
                EXPECT_NEAR(sum, total.g[k], sumRoundOff * std::max(1.0, total.g[k]))
                    << where << ", bin " << k;
            }
        }
}

// Uniformly random positions, whatever the species: every partial is 1 within its block errors,
// like pairs and unlike alike (N_a²/2 in place of N_a(N_a − 1)/2 would put g_BB of the 50 B
// bodies here 2 % low, an unlike pair counted twice g_AB 100 % high).
TEST(MixtureRdf, AnIdealMixturesPartialsAreOneWithinTheirErrors) {
    const int n = 200, frames = 160, blocks = 8;
    const double length = 20.0, bin = 0.5;
    const auto samples = randomFrames(frames, n, length, 5);
    const SpeciesLabels l = labels({150, 50});
    RdfAccumulator acc(n, length, bin, 0.5 * length, frames, blocks, l);
    for (const auto& f : samples)
        acc.add(f);
    for (int a = 0; a < 2; ++a)
        for (int b = a; b < 2; ++b) {
            const RadialDistribution g = acc.partial(a, b);
            double z2 = 0.0, counted = 0.0, expected = 0.0;
            int bins = 0;
            for (std::size_t k = 0; k < g.g.size(); ++k) {
                const double ideal = frames * acc.pairs(a, b) *
                                     shellVolume(k * bin, (k + 1) * bin) / std::pow(length, 3);
                counted += g.g[k] * ideal, expected += ideal;
                if (ideal < 400.0) continue; // too few pairs for a Gaussian error
                ASSERT_GT(g.err[k], 0.0);
                const double z = (g.g[k] - 1.0) / g.err[k];
                EXPECT_LT(std::abs(z), idealSigmas) << "pair " << a << b << ", r = " << g.r[k];
                z2 += z * z, ++bins;
            }
            ASSERT_GT(bins, 10);
            EXPECT_GT(z2 / bins, zSquaredLow) << "pair " << a << b;
            EXPECT_LT(z2 / bins, zSquaredHigh) << "pair " << a << b;
            // All pairs within L/2 pooled: 1 within a few of its Poisson errors.
            EXPECT_NEAR(counted / expected, 1.0, 5.0 / std::sqrt(expected)) << "pair " << a << b;
        }
}

namespace {

constexpr double intervalPs = 0.01;

/// Free flight in straight lines, species a at speed speeds[a] in a random direction: each
/// species' MSD is v_a² t², its VACF 1.
std::vector<Snapshot> ballistic(int frames, const SpeciesLabels& l,
                                const std::vector<double>& speeds, double length) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> uniform(0.0, length);
    const int n = static_cast<int>(l.ofBody.size());
    auto samples = synthetic::emptySamples(frames, n, units::fromPs(intervalPs), length);
    for (int i = 0; i < n; ++i) {
        const Vec3 r0(uniform(rng), uniform(rng), uniform(rng));
        const Vec3 v = speeds[l.ofBody[i]] * synthetic::unitVector(rng); // Å per time unit
        for (int k = 0; k < frames; ++k) {
            samples[k].position[i] = r0 + v * samples[k].time;
            samples[k].velocity[i] = v;
        }
    }
    return samples;
}

StreamingOptions smallOptions(int follow) {
    StreamingOptions o;
    o.blocks = 4, o.lagsPerLevel = 4, o.rdfBinAngstrom = 0.5, o.followBodies = follow;
    return o;
}

} // namespace

// Species moving at 1, 2 and 3 Å per time unit: msd_A = v_A² t², msd_B = v_B² t², … in msd.csv
// (t in ps, so t/Δ of a time unit), vacf_a = 1, and the total MSD their mean over the followed
// bodies; the same whether the whole samples are given or only the followed bodies (some of
// each species when fewer are followed than there are).
TEST(MixtureCorrelations, EachSpeciesMsdIsItsOwnSpeedSquaredTimesTSquared) {
    const std::vector<double> speeds{1.0, 2.0, 3.0};
    const SpeciesLabels l = labels({40, 15, 5});
    const auto samples = ballistic(64, l, speeds, 30.0);
    for (const int follow : {0, 12}) {
        RunAnalysis whole(60, 30.0, intervalPs, 64, smallOptions(follow), l);
        RunAnalysis parts(60, 30.0, intervalPs, 64, smallOptions(follow), l);
        for (const auto& s : samples) {
            whole.add(s);
            Snapshot followed;
            followed.time = s.time, followed.boxLength = s.boxLength;
            for (const int b : parts.followedBodies()) {
                followed.position.push_back(s.position[b]);
                followed.velocity.push_back(s.velocity[b]);
                followed.axis.push_back(s.axis[b]);
            }
            parts.add(followed, [&s](int b) { return s.position[b]; });
        }
        const ScratchDirectory a("whole"), b("parts");
        const auto summary = whole.write(a.path);
        parts.write(b.path);
        for (const char* f : {"rdf.csv", "vacf.csv", "msd.csv"})
            EXPECT_EQ(readWholeFile(a.path / f), readWholeFile(b.path / f)) << f;
        const CsvTable msd = readCsv(a.path / "msd.csv"), vacf = readCsv(a.path / "vacf.csv");
        ASSERT_EQ(msd.header,
                  (std::vector<std::string>{"t_ps", "msd_angstrom2", "err", "msd_A", "err_A",
                                            "msd_B", "err_B", "msd_C", "err_C"}));
        ASSERT_EQ(vacf.header, (std::vector<std::string>{"t_ps", "c", "err", "vacf_A", "err_A",
                                                         "vacf_B", "err_B", "vacf_C", "err_C"}));
        ASSERT_GE(msd.rows(), 10); // lags 0 … 3, then 4, 6, 8, … up to 31 (p = 4)
        // The followed bodies' mean v², species by species.
        double v2 = 0.0;
        for (const int body : whole.followedBodies())
            v2 += speeds[l.ofBody[body]] * speeds[l.ofBody[body]];
        v2 /= double(whole.followedBodies().size());
        for (int row = 0; row < msd.rows(); ++row) {
            const double t = units::fromPs(msd.columns[0][row]);
            for (int s = 0; s < 3; ++s) {
                const double expected = speeds[s] * speeds[s] * t * t;
                EXPECT_NEAR(msd.columns[3 + 2 * s][row], expected,
                            freeFlightRelative * std::max(1.0, expected))
                    << "species " << s << ", t = " << msd.columns[0][row] << ", follow " << follow;
                EXPECT_NEAR(vacf.columns[3 + 2 * s][row], 1.0, freeFlightRelative);
            }
            EXPECT_NEAR(msd.columns[1][row], v2 * t * t,
                        freeFlightRelative * std::max(1.0, v2 * t * t));
        }
        for (const char* name : {"A", "B", "C"}) {
            ASSERT_TRUE(summary["diffusion"]["species"].contains(name)) << name;
            EXPECT_GE(summary["diffusion"]["species"][name]["followed_bodies"].get<int>(), 1);
        }
    }
}

// Rods among spheres (core/species_rotor.hpp): two rod species A and B turn uniformly at their own
// ω, so s(0)·s(t) = cos ωt for each body; the spheres C never move their axes. The OACF is over
// the rods alone, the mean of A's and B's weighted by their bodies, (n_A cos ω_A t + n_B cos
// ω_B t)/(n_A + n_B) (not the spheres' share of 1 added), with each rod species' own columns
// beside it and none for the spheres. Without the labels' flags (a scene of one kind, or rods
// alone) the summary keeps its OACF entry.
TEST(MixtureCorrelations, TheOacfIsOverTheSpeciesThatTurn) {
    SpeciesLabels l = labels({12, 20, 32});
    l.fixedAxis = {false, false, true};
    const double omega[] = {2.0, 0.7}; // rad per time unit
    auto samples = ballistic(64, l, {1.0, 1.2, 1.5}, 30.0);
    std::mt19937_64 rng(5);
    for (int i = 0; i < 64; ++i) {
        const Vec3 s0 = synthetic::unitVector(rng);
        const Vec3 sideways = s0.cross(synthetic::unitVector(rng)).normalized();
        const int a = l.ofBody[i];
        for (auto& f : samples)
            f.axis[i] = a == 2 ? s0
                               : Vec3(s0 * std::cos(omega[a] * f.time) +
                                      sideways * std::sin(omega[a] * f.time));
    }
    RunAnalysis a(64, 30.0, intervalPs, 64, smallOptions(0), l);
    for (const auto& f : samples)
        a.add(f);
    const ScratchDirectory dir("oacf");
    const auto summary = a.write(dir.path);
    const CsvTable oacf = readCsv(dir.path / "oacf.csv");
    ASSERT_EQ(oacf.header, (std::vector<std::string>{"t_ps", "c1", "c1_err", "c2", "c2_err", "c1_A",
                                                     "c1_err_A", "c2_A", "c2_err_A", "c1_B",
                                                     "c1_err_B", "c2_B", "c2_err_B"}));
    ASSERT_GE(oacf.rows(), 10);
    const auto p2 = [](double c) { return 1.5 * c * c - 0.5; };
    for (int row = 0; row < oacf.rows(); ++row) {
        const double t = units::fromPs(oacf.columns[0][row]);
        const double cA = std::cos(omega[0] * t), cB = std::cos(omega[1] * t);
        EXPECT_NEAR(oacf.columns[1][row], (12.0 * cA + 20.0 * cB) / 32.0, 1e-9) << t;
        EXPECT_NEAR(oacf.columns[3][row], (12.0 * p2(cA) + 20.0 * p2(cB)) / 32.0, 1e-9) << t;
        EXPECT_NEAR(oacf.columns[5][row], cA, 1e-9);
        EXPECT_NEAR(oacf.columns[7][row], p2(cA), 1e-9);
        EXPECT_NEAR(oacf.columns[9][row], cB, 1e-9);
        // Every body of a species turns alike: no spread between blocks, errors at round-off.
        for (const int e : {2, 4, 6, 8, 10, 12})
            EXPECT_LT(oacf.columns[e][row], 1e-9);
    }
    EXPECT_EQ(summary["oacf"]["species"], nlohmann::json::array({"A", "B"}));
    EXPECT_NEAR(summary["oacf"]["c1_0"].get<double>(), 1.0, 1e-12);

    // The same axes with no flags: every body in the OACF, and the summary's entry kept.
    l.fixedAxis.clear();
    RunAnalysis plain(64, 30.0, intervalPs, 64, smallOptions(0), l);
    for (const auto& f : samples)
        plain.add(f);
    const ScratchDirectory plainDir("oacf-plain");
    const auto plainSummary = plain.write(plainDir.path);
    EXPECT_NEAR(plainSummary["oacf"]["c1_0"].get<double>(), 1.0, 1e-12);
    EXPECT_FALSE(plainSummary["oacf"].contains("species"));
    const CsvTable all = readCsv(plainDir.path / "oacf.csv");
    ASSERT_EQ(all.header.size(), 5u);
    const double t = units::fromPs(all.columns[0][5]);
    EXPECT_NEAR(all.columns[1][5],
                (12.0 * std::cos(omega[0] * t) + 20.0 * std::cos(omega[1] * t) + 32.0) / 64.0,
                1e-9);
}

// Every species is followed, however few its bodies, in its share of the followed bodies.
TEST(MixtureCorrelations, EverySpeciesHasFollowedBodies) {
    const SpeciesLabels l = labels({995, 3, 2});
    const auto follow = followedPerSpecies(l.ofBody, 3, 100);
    std::vector<int> perSpecies(3, 0);
    for (std::size_t k = 0; k < follow.size(); ++k) {
        if (k > 0) {
            EXPECT_LT(follow[k - 1], follow[k]);
        }
        ++perSpecies[l.ofBody[follow[k]]];
    }
    EXPECT_EQ(perSpecies, (std::vector<int>{99, 1, 1}));
    EXPECT_EQ(followedPerSpecies(l.ofBody, 3, 0).size(), 1000u);
    EXPECT_EQ(followedPerSpecies(l.ofBody, 3, 5000).size(), 1000u);
}

namespace {

struct Written {
    std::map<std::string, std::string> files;
    std::string summary;
};

Written writtenBy(const RunAnalysis& a, const std::string& name) {
    const ScratchDirectory dir(name);
    Written w;
    w.summary = a.write(dir.path).dump();
    for (const char* f : {"rdf.csv", "vacf.csv", "msd.csv"})
        w.files[f] = readWholeFile(dir.path / f);
    return w;
}

} // namespace

// A mixture's analysis cut after any sample, its state restored into a new one and continued,
// writes the same bytes (the partial histograms and the species' correlations in the state); the
// state does not grow with the samples; a plain analysis's state and a mixture's do not fit each
// other (refused, never misread).
TEST(MixtureState, ARestoredMixtureAnalysisWritesTheSameBytes) {
    const SpeciesLabels l = labels({30, 10});
    auto samples = randomFrames(40, 40, 16.0, 9);
    const auto moving = ballistic(40, l, {0.5, 1.5}, 16.0);
    for (std::size_t k = 0; k < samples.size(); ++k)
        samples[k].velocity = moving[k].velocity, samples[k].time = moving[k].time;
    StreamingOptions o = smallOptions(12);
    o.rdfEvery = 3;
    auto fresh = [&](const SpeciesLabels& species) {
        return std::make_unique<RunAnalysis>(40, 16.0, intervalPs, 40, o, species);
    };
    auto whole = fresh(l);
    const std::size_t size = whole->state().size();
    for (const auto& s : samples)
        whole->add(s);
    EXPECT_EQ(whole->state().size(), size);
    const Written expected = writtenBy(*whole, "whole");
    for (const long cut : {1L, 4L, 5L, 9L, 17L, 39L}) {
        auto before = fresh(l);
        for (long k = 0; k < cut; ++k)
            before->add(samples[k]);
        const auto state = before->state();
        auto after = fresh(l);
        after->restore(state);
        for (long k = cut; k < long(samples.size()); ++k)
            after->add(samples[k]);
        const Written got = writtenBy(*after, "cut");
        EXPECT_EQ(got.summary, expected.summary) << "cut after " << cut;
        for (const auto& [name, bytes] : expected.files)
            EXPECT_EQ(got.files.at(name), bytes) << name << ", cut after " << cut;
    }
    auto plain = fresh({});
    for (long k = 0; k < 5; ++k)
        plain->add(samples[k]);
    EXPECT_LT(plain->state().size(), size);
    EXPECT_THROW(fresh(l)->restore(plain->state()), std::invalid_argument);
    EXPECT_THROW(fresh({})->restore(whole->state()), std::invalid_argument);
    // Other species counts: other partial histograms' lengths or other followed bodies.
    EXPECT_THROW(fresh(labels({20, 10, 10}))->restore(whole->state()), std::invalid_argument);
}

// A scene of one kind of body: the columns it always had, no species entries in the summary;
// a mixture's columns come after them, in the documented order.
TEST(MixtureFiles, APlainSceneWritesTheColumnsItAlwaysDid) {
    const SpeciesLabels l = labels({20, 12});
    const auto samples = ballistic(16, l, {1.0, 1.0}, 12.0);
    for (const bool mixture : {false, true})
        for (const double beta : {0.0, 0.4}) {
            StreamingOptions o = smallOptions(0);
            o.beta = beta;
            RunAnalysis a(32, 12.0, intervalPs, 16, o, mixture ? l : SpeciesLabels{});
            for (const auto& s : samples) {
                // What an engine puts into its terracing profile on a g(r) frame.
                if (beta > 0.0 && a.wantsPositions()) a.terracing()->add(1.0, 0.1);
                a.add(s);
            }
            const ScratchDirectory dir("headers");
            const auto summary = a.write(dir.path);
            std::vector<std::string> rdf{"r_angstrom", "g", "err"};
            if (beta > 0.0) rdf.insert(rdf.end(), {"g_continuous", "err_continuous"});
            std::vector<std::string> vacf{"t_ps", "c", "err"}, msd{"t_ps", "msd_angstrom2", "err"};
            if (mixture) {
                rdf.insert(rdf.end(), {"g_A_A", "err_A_A", "g_A_B", "err_A_B", "g_B_B", "err_B_B"});
                vacf.insert(vacf.end(), {"vacf_A", "err_A", "vacf_B", "err_B"});
                msd.insert(msd.end(), {"msd_A", "err_A", "msd_B", "err_B"});
            }
            EXPECT_EQ(readCsv(dir.path / "rdf.csv").header, rdf);
            EXPECT_EQ(readCsv(dir.path / "vacf.csv").header, vacf);
            EXPECT_EQ(readCsv(dir.path / "msd.csv").header, msd);
            EXPECT_EQ(summary["diffusion"].contains("species"), mixture);
            EXPECT_EQ(summary["rdf"].contains("partials"), mixture);
        }
}

// Labels that are not a mixture of these bodies are refused when the analysis is built.
TEST(MixtureFiles, LabelsThatDoNotFitAreRefused) {
    SpeciesLabels l = labels({20, 12});
    const StreamingOptions o = smallOptions(0);
    EXPECT_THROW(RunAnalysis(31, 12.0, intervalPs, 16, o, l), std::invalid_argument);
    l.ofBody[3] = 2;
    EXPECT_THROW(RunAnalysis(32, 12.0, intervalPs, 16, o, l), std::invalid_argument);
    SpeciesLabels one = labels({32});
    EXPECT_THROW(RunAnalysis(32, 12.0, intervalPs, 16, o, one), std::invalid_argument);
}

} // namespace test_mixture_analysis
