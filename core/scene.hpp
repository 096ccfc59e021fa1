#pragma once
// A scene: everything that defines a run, read from JSON with every key validated. An unknown key,
// a wrong type or an out-of-range value is a SceneError naming the file and the dotted key; there
// are no silent defaults for keys that are present. Absent keys take the documented defaults,
// which are the paper's dense rods (DESIGN.md "The rod model"). A key that the scene's body kind
// has no use for is refused rather than ignored, a repeated key is refused (JSON would keep the
// last), and every interval must fit in the run and lie on the engine's time grid. Each section
// has one reader that owns its keys (core/scene_sections.hpp); the engines' sections, dmd and
// smd, are carried as given and read by the engines' modules (Scene::dmd).
#include "core/vec.hpp"
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace terrace {

class SceneError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// One body of an explicit initial configuration (state.particles). After validation `axis` and
/// `orientation` agree: the axis is the image of the body z axis, axis = q * ẑ. Given only an
/// orientation, any body with an axis takes it from q; a linear rotor or symmetric top given only
/// an axis gets the rotation of least angle taking ẑ to it (the spin about the axis is then
/// immaterial); an asymmetric top must be given its orientation; spheres take neither, nor omega.
struct ParticleSpec {
    Vec3 r = Vec3::Zero();           // Å
    Vec3 v = Vec3::Zero();           // Å/ps
    Vec3 axis = Vec3::UnitZ();       // unit long axis
    std::optional<Quat> orientation; // body -> lab ([w, x, y, z])
    Vec3 omega = Vec3::Zero();       // lab angular velocity, rad/ps
    int species = -1;                // index into Scene::species (a mixture's); -1 without
};

/// One interaction site of a rigid site-site molecule (body.sites): its position in the body's
/// principal frame relative to the centre of mass (Å), its mass (g/mol) and its Lennard-Jones ε
/// (kJ/mol) and σ (Å); unlike sites interact by Lorentz–Berthelot mixing.
struct SiteSpec {
    Vec3 r = Vec3::Zero();
    double mass = 0.0;
    double epsilon = 0.0;
    double sigma = 0.0;
};

/// One species of a mixture of spheres (Scene::species): its share of the bodies and its own
/// Lennard-Jones ε, σ and mass in the scene's units (potential.epsilon, potential.sigma,
/// body.mass), so that a mixture given in ε_AA, σ_AA and m_A, as the literature gives them, is
/// typed as printed.
struct SpeciesSpec {
    std::string name;
    double fraction = 0.0; // of state.n; the fractions add up to 1
    double epsilon = 1.0;  // ε
    double sigma = 1.0;    // σ
    double mass = 1.0;     // body.mass
    // rod-lj only (rods among spheres, core/species_rotor.hpp): linear | sphere, and a linear
    // species' moment of inertia in body.inertia's first moment. Empty for a mixture of spheres.
    std::string kind;
    double inertia = 1.0;
};

/// The parameters of one unlike pair (potential.pairs), in place of Lorentz–Berthelot's mixing
/// of its species' own (ε, σ as for SpeciesSpec).
struct SpeciesPairSpec {
    std::string first, second;
    double epsilon = 1.0;
    double sigma = 1.0;
};

struct Scene {
    std::string name = "dense-rods";
    std::uint64_t seed = 1;
    // real | lj: the units the keys below are read in and the results written in
    // (core/scene_units.hpp). The fields always hold real units, whatever the scene was written in.
    std::string units = "real";

    struct Body {
        std::string kind = "linear";     // sphere | linear | symmetric | asymmetric
        double mass = 18.0;              // g/mol
        Vec3 inertia{1.154, 1.154, 0.0}; // g/mol Å², principal moments
        // potential.kind = sites only. Mass and inertia follow from the sites unless given (then
        // they must agree); the sites must be given in the principal frame.
        std::vector<SiteSpec> sites;
    } body;

    struct Potential {
        std::string kind = "rod-lj"; // rod-lj | lj | gay-berne | sites | steps
        // The scene's energy and length units: T* = kT/ε and ρ* = Nσ³/L³, the cutoff in σ. For
        // gay-berne they are also the potential's ε0 and σ0 (= σ_s); for sites the units only,
        // the sites carrying their own.
        double epsilon = 3.0; // kJ/mol
        double sigma = 3.035; // Å
        double zeta = 1.0;    // Å (rod-lj only)
        // gay-berne only (core/gay_berne_potential.hpp): κ = σ_e/σ_s, κ' = ε_s/ε_e, μ, ν; the
        // default is the standard GB(3, 5, 2, 1).
        double kappa = 3.0;
        double kappa_prime = 5.0;
        double mu = 2.0;
        double nu = 1.0;
        // Smoothed cutoff [r_l, r_u] in σ (paper eqs. 22-23): the model is g(r)·U, which SMD
        // integrates and DMD terraces (core/smoothed_potential.hpp). Key: "cutoff": [r_l, r_u].
        double r_l = 2.5;
        double r_u = 3.0;
        // lj with species only: the cutoff in each pair's own σ_ab instead of σ, so that each
        // pair switches on [r_l σ_ab, r_u σ_ab] (Kob and Andersen cut at 2.5 σ_ab). Key:
        // "cutoff_per_pair".
        bool cutoff_per_pair = false;
        // steps only (core/step_table.hpp): the table, resolved from the one given or named
        // (square_well, square_shoulder, chapela_lj, lj), radii in σ, energies in ε, sorted by
        // decreasing radius; hard_core in σ, 0 for none. The first radius is the cutoff.
        std::vector<double> step_radii;
        std::vector<double> step_energies;
        double hard_core = 0.0;
        // lj with species only: unlike pairs' own parameters (core/lj_mixture.hpp).
        std::vector<SpeciesPairSpec> pairs;
    } potential;

    // A mixture of spheres under lj or steps (core/species_sphere.hpp), or of rods and spheres
    // under rod-lj (core/species_rotor.hpp, core/rod_mixture.hpp): two to maxSpecies species,
    // empty for one kind of body. Bodies take their species at random, by the scene's
    // seed, in the numbers speciesCounts gives.
    std::vector<SpeciesSpec> species;

    struct State {
        int n = 512;
        double density = 0.5;                // ρσ³
        double temperature = 1.4;            // T* = kT/ε
        std::string orientations = "random"; // random | aligned (lattice starts only)
        // The start's lattice (core/start_lattice.hpp): sc | fcc | bcc (lattice starts only).
        std::string lattice = "sc";
        // The lattice cell's length along z over its width: elongated bodies started aligned
        // along z sit end to end that much farther apart than side by side (lattice starts only).
        double lattice_aspect = 1.0;
        std::vector<ParticleSpec> particles; // explicit start; overrides the lattice when given
    } state;

    std::string engine = "dmd"; // dmd | smd

    // The engines' own sections, carried as given (an object; --set overrides applied): their
    // keys, defaults and checks belong to dmd/section.hpp and smd/parameters.hpp, whose checks
    // whoever runs a scene calls (cli/scene_check.hpp), and which write the section back
    // resolved, every key given.
    nlohmann::json dmd = nlohmann::json::object();
    nlohmann::json smd = nlohmann::json::object();

    // Every interval and length is honoured exactly or refused. Lengths are honoured as typed:
    // equilibration's last thermostat interval is cut short where equilibrate_ps is not a whole
    // number of them (it still ends on a rescale), and production runs on, unsampled, past its
    // last whole sample to time_ps. sample_fs must fit in the run; sample_fs and thermostat_fs
    // are >= 0.01 fs; under SMD, intervals and lengths are whole multiples of smd.dt_fs
    // (smd/parameters.hpp; relative tolerance limits::gridTolerance on each ratio). The
    // defaults are whole multiples of 9 fs, so whole numbers of SMD steps at dt = 0.2, 0.5, 1,
    // 1.8 and 3 fs.
    struct Run {
        double equilibrate_ps = 1.8; // 200 thermostat intervals
        double time_ps = 9.0;        // 1000 samples
        double sample_fs = 9.0;
        // Equilibration rescales v and ω to the scene temperature every thermostat_fs, over
        // equilibrate_ps / thermostat_fs whole intervals; the default equals the default
        // sample_fs, so that default runs are unchanged, but sample_fs no longer sets it.
        double thermostat_fs = 9.0;
        // The heat bath (core/heat_bath.hpp), in equilibration and production: none (NVE
        // production, equilibration by the rescales above), andersen (each body's velocities
        // drawn afresh as a Poisson process of rate_per_ps) or csvr (Bussi's stochastic
        // rescaling, kinetic energy relaxing in tau_fs). Key: run.heat_bath, "none" or an object
        // {"kind": ..., its one parameter}; written back only when not none.
        struct HeatBath {
            std::string kind = "none"; // none | andersen | csvr
            double rate_per_ps = 0.0;  // andersen: collisions per body per ps, > 0
            double tau_fs = 0.0;       // csvr: > 0 (under SMD >= smd.dt_fs)
        } heat_bath;
    } run;

    // Output intervals are whole multiples of run.sample_fs, no longer than run.time_ps.
    struct Output {
        double trajectory_every_fs = 0.0; // 0 = no trajectory
        // xyz: extended XYZ (trajectory.xyz), read by `terrace analyse`, OVITO and ASE; gsd:
        // HOOMD's GSD (trajectory.gsd, core/gsd_frame.hpp), read by OVITO, freud and gsd, with
        // orientations and shapes a viewer draws.
        std::string trajectory_format = "xyz";
        double restart_every_ps = 0.0; // 0 = no restart files
        // Rows of thermo.csv (energies, temperature, pressure; production only), 0 = none. A
        // scene file without the key gets about 100 rows (core/thermo_interval.hpp).
        double thermo_every_fs = 0.0;
    } output;

    // The analysis, accumulated as the run goes (analysis/run_analysis.hpp): memory independent
    // of the run's length, time O(N) per sample.
    struct Analysis {
        int blocks = 8;          // blocks behind every error bar, >= 2
        double max_lag_ps = 0.0; // longest lag of the time correlations; 0 = half the run
        // g(r) out to this distance, σ, at most L/2 (0: L/2); when absent 5, or L/2 in a box
        // narrower than 10 σ.
        double rdf_max = 5.0;
        double rdf_bin_angstrom = 0.05;
        int rdf_every = 10;       // samples between g(r) frames (90 fs by default)
        int follow_bodies = 4096; // bodies the time correlations follow; 0 = all
        int lags_per_level = 16;  // lags per level of the multiple-tau grid, even, >= 4
    } analysis;

    // One-line notes on values that are legal but probably not meant, left by the readers of
    // the engines' sections when they resolve them (sceneWarnings).
    std::vector<std::string> warnings;

    double kT() const { return state.temperature * potential.epsilon; } // kJ/mol
    double boxLength() const;                                           // Å, from n and density
};

/// The lowest value the scene's pair potential can take, kJ/mol (a bound for site-site models).
double sceneMinimumEnergy(const Scene& s);

/// How many bodies of each species (Scene::species, in its order) among `n`: the fractions'
/// shares rounded by largest remainder, so that they add up to n. Empty without species.
std::vector<int> speciesCounts(const Scene& s, int n);

/// The built-in default scene: the paper's dense rods (N 512, ρ* 0.5, T* 1.4), as a scene file
/// without keys resolves (thermo.csv at its default interval, where Scene{} writes none).
Scene defaultScene();

/// Parse and validate; `origin` names the source in error messages (a file path or "<default>").
/// `overrides` are "dotted.key=value" strings applied before validation (value parsed as JSON,
/// or taken as a string when it is not valid JSON).
Scene sceneFromJson(const nlohmann::json& j, const std::string& origin,
                    const std::vector<std::string>& overrides = {});
Scene loadScene(const std::string& path, const std::vector<std::string>& overrides = {});

/// A "dotted.key=value" override split into its key and value: the value is JSON where the text
/// parses as JSON, otherwise the bare string (smd, heap). nullopt when there is no '=' or no key.
std::optional<std::pair<std::string, nlohmann::json>> parseOverride(const std::string& assignment);

/// The fully resolved scene, every key written out (recorded next to every run's output).
nlohmann::json toJson(const Scene& s);

/// One-line warnings for values that are legal but probably not meant (e.g. explicit dmd.levels
/// that leave out the attractive well), as the sections' readers left them in s.warnings; empty
/// when there is nothing to say.
std::vector<std::string> sceneWarnings(const Scene& s);

/// Limits of what a run can represent, each refused with its reason (core/scene_*.cpp).
namespace limits {
/// Samples and thermostat intervals below this resolve nothing: the fastest thermal motion the
/// time grid admits (minThermalTimeFs) changes by < 10 % between them.
inline constexpr double minIntervalFs = 0.01;
/// A thermal body must take at least this long to cross σ (σ·sqrt(m/kT)) or to turn one radian
/// (sqrt(I/kT)); faster motion lies below the finest horizon, and kT/m overflows long before.
inline constexpr double minThermalTimeFs = 0.1;
/// Explicit positions within this many box lengths of the origin: the wrap into the box keeps
/// ~10 of the 16 digits at 1e6 box lengths, no more.
inline constexpr double maxPositionInBoxLengths = 1e6;
/// Relative tolerance on the ratio of an interval to the grid it must lie on (9/1.8 is not
/// exact in binary).
inline constexpr double gridTolerance = 1e-9;

} // namespace limits

} // namespace terrace
