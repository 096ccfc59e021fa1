#include "analysis/replicas.hpp"
#include "analysis/block_average.hpp"
#include "analysis/csv.hpp"
#include "analysis/dynamic_correlations.hpp"
#include "analysis/rdf.hpp"
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace terrace::analysis {

namespace {

/// Sample grids of replicas agree to the round-off of reading times back from text.
constexpr double gridTolerance = 1e-9;

/// Point-by-point mean over replicas and its standard error (equal weights).
struct Combined {
    std::vector<double> value, err;
};
Combined combine(const std::vector<std::vector<double>>& perReplica) {
    const std::size_t points = perReplica.front().size(), r = perReplica.size();
    const std::vector<double> weights(r, 1.0);
    Combined c{std::vector<double>(points, 0.0), std::vector<double>(points, 0.0)};
    std::vector<double> at(r);
    for (std::size_t k = 0; k < points; ++k) {
        for (std::size_t i = 0; i < r; ++i)
            at[i] = perReplica[i][k];
        c.value[k] = blockRatio(at, weights).mean;
        c.err[k] = blockError(at, weights, c.value[k]);
    }
    return c;
}

void checkReplicas(const std::vector<std::vector<Snapshot>>& replicas) {
    if (replicas.size() < 2) throw std::invalid_argument("replica errors need ≥ 2 replicas");
    const auto& first = replicas.front();
    const double dt = sampleIntervalPs(first);
    for (std::size_t r = 1; r < replicas.size(); ++r) {
        const auto& other = replicas[r];
        if (other.size() != first.size() || other.front().size() != first.front().size() ||
            other.front().boxLength != first.front().boxLength ||
            std::abs(sampleIntervalPs(other) - dt) > gridTolerance * dt)
            throw std::invalid_argument("replica " + std::to_string(r) +
                                        ": samples, bodies, box or sample interval differ from "
                                        "replica 0");
    }
}

} // namespace

nlohmann::json writeReplicaCorrelations(const std::vector<std::vector<Snapshot>>& replicas,
                                        const std::filesystem::path& dir, const Options& options) {
    checkReplicas(replicas);
    const auto& first = replicas.front();
    const int t = static_cast<int>(first.size()), n = first.front().size();
    if (t < 4 || n < 2 || options.blocks < 2 || !(options.rdfBinAngstrom > 0.0) ||
        !(options.maxLagPs >= 0.0))
        throw std::invalid_argument("writeReplicaCorrelations: need ≥ 4 samples, ≥ 2 bodies, "
                                    "≥ 2 blocks, a positive bin and a lag ≥ 0");
    const double dtPs = sampleIntervalPs(first);
    const int blocks = std::min(options.blocks, t / 2);
    const int maxLag = lagFor(options.maxLagPs, dtPs, t, blocks);
    const bool rotating = axesRotate(first);

    std::vector<std::vector<double>> g, vacf, c1, c2, msd, diffusion(1), greenKubo(1);
    RadialDistribution grid;
    SampledCurve lags;
    for (const auto& samples : replicas) {
        grid = radialDistribution(samples, options.rdfBinAngstrom, 1);
        g.push_back(grid.g);
        double v2 = 0.0;
        lags = velocityAutocorrelation(samples, maxLag, blocks, &v2);
        vacf.push_back(lags.value);
        greenKubo[0].push_back(detail::greenKuboDiffusion(lags.tPs, lags.value, v2));
        if (rotating) {
            const auto o = orientationalAutocorrelation(samples, maxLag, blocks);
            c1.push_back(o.c1.value);
            c2.push_back(o.c2.value);
        }
        const SampledCurve m = meanSquaredDisplacement(samples, maxLag, std::min(blocks, n));
        msd.push_back(m.value);
        diffusion[0].push_back(diffusionFromMsd(m).coefficient);
    }

    const Combined gr = combine(g), v = combine(vacf), m = combine(msd);
    std::filesystem::create_directories(dir);
    writeCsv(dir / "rdf.csv", {{"r_angstrom", "g", "err"}, {grid.r, gr.value, gr.err}});
    writeCsv(dir / "vacf.csv", {{"t_ps", "c", "err"}, {lags.tPs, v.value, v.err}});
    if (rotating) {
        const Combined o1 = combine(c1), o2 = combine(c2);
        writeCsv(dir / "oacf.csv", {{"t_ps", "c1", "c1_err", "c2", "c2_err"},
                                    {lags.tPs, o1.value, o1.err, o2.value, o2.err}});
    } else {
        std::filesystem::remove(dir / "oacf.csv");
    }
    writeCsv(dir / "msd.csv", {{"t_ps", "msd_angstrom2", "err"}, {lags.tPs, m.value, m.err}});

    grid.g = gr.value, grid.err = gr.err;
    const Combined d = combine(diffusion), gk = combine(greenKubo);
    return {{"replicas", replicas.size()},
            {"samples_per_replica", t},
            {"bodies", n},
            {"sample_interval_ps", dtPs},
            {"max_lag_ps", maxLag * dtPs},
            {"rdf", detail::rdfSummary(grid, 0.4 * first.front().boxLength)},
            {"oacf", rotating ? "written" : "not written: the axes do not change"},
            {"diffusion",
             {{"einstein_angstrom2_per_ps", d.value[0]},
              {"einstein_err", d.err[0]},
              {"green_kubo_angstrom2_per_ps", gk.value[0]},
              {"green_kubo_err", gk.err[0]}}}};
}

} // namespace terrace::analysis
