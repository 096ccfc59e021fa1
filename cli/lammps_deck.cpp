#include "cli/lammps_deck.hpp"
#include "cli/dispatch.hpp"
#include "core/body_orientation.hpp"
#include "core/initial_state.hpp"
#include "core/lj_mixture.hpp"
#include "core/smoothed_potential.hpp"
#include "core/species_sphere.hpp"
#include "core/units.hpp"
#include "dmd/section.hpp"
#include "smd/parameters.hpp"
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace terrace::cli {

namespace {

/// Velocities (Å per time unit) and angular velocities (rad per time unit) in LAMMPS's per fs.
constexpr double perFs = 1.0 / units::fsPerTimeUnit;

std::string number(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", x);
    return text;
}

/// A number in a note, for people: six digits.
std::string shortNumber(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", x);
    return text;
}

std::string vec(const Vec3& v) {
    return number(v.x()) + " " + number(v.y()) + " " + number(v.z());
}

/// A position in the box [0, L)³ and the image it came from (LAMMPS's image flags), so that
/// LAMMPS unwraps it to terrace's unwrapped position (and a rigid molecule to one piece).
struct Wrapped {
    Vec3 x;
    std::array<long long, 3> image;
};
Wrapped wrap(const Vec3& p, double L) {
    Wrapped w;
    for (int c = 0; c < 3; ++c) {
        double n = std::floor(p[c] / L), x = p[c] - n * L;
        if (x >= L) { // p just below a multiple of L rounds up to it
            x -= L;
            n += 1.0;
        }
        if (x < 0.0) x = 0.0;
        w.x[c] = x;
        w.image[c] = static_cast<long long>(n);
    }
    return w;
}
std::string placed(const Vec3& p, double L) {
    const Wrapped w = wrap(p, L);
    return vec(w.x) + " " + std::to_string(w.image[0]) + " " + std::to_string(w.image[1]) + " " +
           std::to_string(w.image[2]);
}

/// The run's steps and the notes on what of it LAMMPS does differently.
struct Timing {
    double dtFs = 0.0, skinAngstrom = 0.0;
    long long equilibrate = 0, production = 0, thermostatEvery = 0, thermoEvery = 0;
};
long long steps(double fs, double dtFs) {
    return std::llround(fs / dtFs);
}
/// The steps of dt in `fs` of the key `key`; a length off the step grid (a DMD scene's, which no
/// step checks) is rounded to the nearest whole step, said in a note.
long long stepsNoted(const char* key, double fs, double dtFs, std::vector<std::string>& notes) {
    const long long n = steps(fs, dtFs);
    if (std::abs(n * dtFs - fs) > limits::gridTolerance * fs)
        notes.push_back(std::string(key) + ": " + shortNumber(fs) +
                        " fs is no whole number of steps of smd.dt_fs = " + shortNumber(dtFs) +
                        " fs; the deck takes " + std::to_string(n) + " steps (" +
                        shortNumber(n * dtFs) + " fs)");
    return n;
}
Timing timing(const Scene& scene, std::vector<std::string>& notes) {
    const smd::SmdSection smd = smd::readSmdSection(scene.smd);
    Timing t;
    t.dtFs = smd.dt_fs;
    t.skinAngstrom = smd.skin * scene.potential.sigma;
    t.equilibrate =
        stepsNoted("run.equilibrate_ps", scene.run.equilibrate_ps * 1000.0, smd.dt_fs, notes);
    t.production = stepsNoted("run.time_ps", scene.run.time_ps * 1000.0, smd.dt_fs, notes);
    t.thermostatEvery =
        std::max(1LL, stepsNoted("run.thermostat_fs", scene.run.thermostat_fs, smd.dt_fs, notes));
    t.thermoEvery =
        std::max(1LL, steps(scene.output.thermo_every_fs > 0.0 ? scene.output.thermo_every_fs
                                                               : scene.run.sample_fs,
                            smd.dt_fs));
    if (scene.engine == "dmd") {
        std::string note = "engine: the scene runs DMD; the deck integrates the continuous model "
                           "with velocity Verlet at smd.dt_fs = " +
                           shortNumber(smd.dt_fs) + " fs (the dmd section is not exported)";
        if (dmd::readDmdSection(scene.dmd).model == "bare")
            note += "; dmd.model = bare (the paper's uncut U terraced) is not what the deck runs";
        notes.push_back(note);
    }
    if (smd.scheme != "verlet")
        notes.push_back("smd.scheme: " + smd.scheme +
                        " is not in LAMMPS; the deck integrates with velocity Verlet (fix nve)");
    return t;
}

/// The first lines of the deck: provenance, units, energies, the differences, the variables.
std::string deckHeader(const Scene& scene, const LammpsDeck& deck, const Timing& t) {
    std::ostringstream o;
    o << "# LAMMPS input written by `terrace export lammps` from scene " << scene.name
      << " (potential " << scene.potential.kind << ", " << deck.atoms << " atoms).\n"
      << "# Units: real (Å, g/mol, fs, kcal/mol, K): terrace's kJ/mol divided by 4.184, its Å/ps "
         "by 1000.\n";
    if (std::isfinite(deck.energyTerrace))
        o << "# Potential energy of the initial state: terrace's model "
          << number(deck.energyTerrace) << " kJ/mol = " << number(deck.energyTerrace * kcalPerKj)
          << " kcal/mol; this deck's model " << number(deck.energyDeck * kcalPerKj)
          << " kcal/mol.\n";
    for (const std::string& m : deck.mapping)
        o << "# Mapped: " << m << "\n";
    for (const std::string& n : deck.notes)
        o << "# Differs from terrace: " << n << "\n";
    o << "# Run: lmp -in in.terrace (in this directory); -var equilibrate 0 -var steps 0 evaluates "
         "the first frame "
         "only.\n"
      << "variable        equilibrate index " << t.equilibrate << "\n"
      << "variable        steps index " << t.production << "\n"
      << "units           real\nboundary        p p p\n";
    return o.str();
}

std::string deckRun(const Timing& t, const std::string& integrator, bool rescale,
                    double temperatureK) {
    std::ostringstream o;
    o << "neigh_modify    every 1 delay 0 check yes\n"
      << "timestep        " << number(t.dtFs) << "\n"
      << "thermo_style    custom step temp pe ke etotal press\n"
      << "thermo_modify   norm no flush yes format float %.15g\n"
      << "thermo          " << t.thermoEvery << "\n"
      << integrator;
    if (rescale)
        o << "# Equilibration as terrace's: velocities rescaled to T every run.thermostat_fs.\n"
          << "if \"${equilibrate} > 0\" then &\n  \"fix rescale all temp/rescale "
          << t.thermostatEvery << " " << number(temperatureK) << " " << number(temperatureK)
          << " 0.0 1.0\" &\n  \"run ${equilibrate}\" \"unfix rescale\"\n";
    o << "run             ${steps}\n";
    return o.str();
}

std::string dataHeader(const Scene& scene, int atoms, int types, double L, const char* extra) {
    std::ostringstream o;
    o << "LAMMPS data file: the initial state of terrace scene " << scene.name
      << " (terrace export lammps), real units\n\n"
      << atoms << " atoms\n"
      << types << " atom types\n"
      << extra << "\n0 " << number(L) << " xlo xhi\n0 " << number(L) << " ylo yhi\n0 " << number(L)
      << " zlo zhi\n\n";
    return o.str();
}

/// The radial pairs of one table: the squared distances in the state and the exact value there.
struct TablePairs {
    std::vector<double> rsq, exact;
    double closest() const {
        double m = std::numeric_limits<double>::infinity();
        for (double x : rsq)
            m = std::min(m, x);
        return std::sqrt(m);
    }
};

/// One radial function to tabulate, with the pairs of the state it acts between.
struct TableJob {
    std::string key, comment;
    Smoothed<LJPotential> model; // g(r)·U_LJ(r), r the distance of the two atoms
    double sigma = 0.0;
    TablePairs pairs;
    RadialTable table;
};

/// U and F = −dU/dr of the smoothed LJ at r: terrace's own evaluation along x.
std::pair<double, double> radial(const Smoothed<LJPotential>& m, double r) {
    const PairForce f = m.evaluate(Vec3(r, 0.0, 0.0), Vec3::UnitZ(), Vec3::UnitZ());
    return {f.U, f.F.x()};
}

/// Tables fine enough that their interpolation moves the state's U by at most tableTolerance
/// (relative to |U|, or to Σ|u| where U cancels to nothing), doubling the points from
/// minTablePoints; returns the points. Unmeasured (measure = false): defaultTablePoints.
int refineTables(std::vector<TableJob>& jobs, bool measure, double& deckEnergy,
                 std::vector<std::string>& notes) {
    double exact = 0.0, scale = 0.0;
    for (const TableJob& j : jobs)
        for (double u : j.pairs.exact) {
            exact += u;
            scale += std::abs(u);
        }
    const double denominator = std::abs(exact) > 1e-3 * scale ? std::abs(exact) : scale;
    for (TableJob& j : jobs) {
        // The inner end: far inside any distance a thermal liquid reaches (U(σ/2) = 16 128 ε),
        // and inside the state's closest pair whatever it is.
        double low = 0.5 * j.sigma;
        if (measure && !j.pairs.rsq.empty()) low = std::min(low, 0.9 * j.pairs.closest());
        j.table.rLow = low;
    }
    int n = measure ? minTablePoints : defaultTablePoints;
    for (;; n *= 2) {
        double deck = 0.0;
        for (TableJob& j : jobs) {
            j.table = tabulate(
                j.key, [&](double r) { return radial(j.model, r); }, j.table.rLow,
                j.model.cut.outer(), n);
            for (double rsq : j.pairs.rsq)
                deck += j.table.lookup(rsq);
        }
        deckEnergy = deck;
        if (!measure) {
            notes.push_back("table: " + std::to_string(n) +
                            " points per table; its interpolation error on the first frame was "
                            "not measured (more than " +
                            std::to_string(measureLimit) + " bodies)");
            return n;
        }
        const double error = denominator > 0.0 ? std::abs(deck - exact) / denominator : 0.0;
        if (error <= tableTolerance) return n;
        if (n >= maxTablePoints) {
            notes.push_back("table: " + std::to_string(n) +
                            " points leave a relative interpolation error of " +
                            shortNumber(error) + " on the first frame's U, above the target " +
                            shortNumber(tableTolerance));
            return n;
        }
    }
}

/// A body count the first-frame measurement covers.
bool measured(int n) {
    return n <= measureLimit;
}

void refuseSmallBox(double L, double reach, const char* what) {
    if (L < 2.0 * reach)
        throw LammpsRefusal("state.density: the box (" + shortNumber(L) +
                            " Å) is narrower than twice " + what + " (" + shortNumber(reach) +
                            " Å): LAMMPS would count a pair's periodic images, terrace only the "
                            "nearest");
}

// ---- Lennard-Jones spheres: one kind, or a mixture
// ------------------------------------------------

/// The atom types of a sphere deck, each with its mass: one for a single kind, one per species of
/// a mixture; and one table per unordered pair of types.
struct SphereTypes {
    std::vector<std::string> names; // the species (empty for a single kind)
    std::vector<double> masses;     // g/mol, per type
    std::vector<TableJob> jobs;
    std::vector<std::vector<int>> jobOf; // [a][b]: the table of types a and b
};

/// The table of one pair of types: terrace's smoothed LJ with the pair's ε and σ.
TableJob ljTableJob(const std::string& key, const std::string& pair, const LJPotential& lj,
                    const SmoothedCutoff& cut) {
    TableJob j;
    j.key = key;
    j.comment = "terrace's smoothed Lennard-Jones g(r)·U_LJ(r)" + pair +
                ", eps = " + number(lj.epsilon) + " kJ/mol, sigma = " + number(lj.sigma) +
                " Å, switched on [" + number(cut.inner()) + ", " + number(cut.outer()) +
                "] Å (core/smoothed_cutoff.hpp); r (Å), U (kcal/mol), F = -dU/dr";
    j.model = Smoothed<LJPotential>{lj, cut};
    j.sigma = lj.sigma;
    return j;
}

SphereTypes sphereTypes(const Scene& scene) {
    SphereTypes t;
    const SmoothedCutoff cut = sceneCutoff(scene);
    if (scene.species.empty()) {
        t.masses = {scene.body.mass};
        t.jobs = {ljTableJob("TERRACE_LJ", "", ljPotential(scene), cut)};
        t.jobOf = {{0}};
        return t;
    }
    // The model both engines run: each pair's switch is the one it answers (cutOfPair).
    const Smoothed<LJMixture> model{ljMixture(scene), cut};
    const LJMixture& mixture = model.bare;
    const BodyParams params = bodyParams(scene);
    const int ns = mixture.species;
    t.jobOf.assign(ns, std::vector<int>(ns, 0));
    for (int a = 0; a < ns; ++a) {
        t.names.push_back(scene.species[a].name);
        t.masses.push_back(params.speciesMass[a]);
        for (int b = a; b < ns; ++b) {
            const std::string pair = scene.species[a].name + "_" + scene.species[b].name;
            t.jobOf[a][b] = t.jobOf[b][a] = static_cast<int>(t.jobs.size());
            t.jobs.push_back(ljTableJob("TERRACE_LJ_" + pair, " of " + pair,
                                        {mixture.pairEpsilon(a, b), mixture.pairSigma(a, b)},
                                        model.cutOfPair(a, b)));
        }
    }
    return t;
}

/// The deck of Lennard-Jones spheres of kind K under `model`: Sphere and the scene's one LJ, or
/// SpeciesSphere and a mixture's, each species an atom type with its mass and each pair of
/// species a table of its own ε and σ, on the one smoothed cutoff or on the pair's own.
template <BodyKind K, class Model> LammpsDeck sphereDeck(const Scene& scene, const Model& model) {
    LammpsDeck deck;
    const auto sys = buildInitialState<K>(scene, model);
    const double L = sys.box.length;
    refuseSmallBox(L, model.range(), "the cutoff r_u");
    const Timing t = timing(scene, deck.notes);
    const int n = sys.size();
    deck.atoms = n;
    const bool measure = measured(n);
    SphereTypes types = sphereTypes(scene);
    const int nt = static_cast<int>(types.masses.size());
    const auto typeOf = [](const typename K::State& b) -> int {
        if constexpr (requires { b.species; })
            return b.species;
        else
            return 0;
    };

    deck.energyTerrace = std::numeric_limits<double>::quiet_NaN();
    if (measure) {
        const double cut2 = model.range() * model.range();
        for (int i = 0; i < n; ++i)
            for (int j = i + 1; j < n; ++j) {
                const auto &bi = sys.bodies[i], &bj = sys.bodies[j];
                const Vec3 rij = sys.box.minimumImage(bi.r - bj.r);
                if (rij.squaredNorm() >= cut2) continue;
                TablePairs& pairs = types.jobs[types.jobOf[typeOf(bi)][typeOf(bj)]].pairs;
                pairs.rsq.push_back(rij.squaredNorm());
                pairs.exact.push_back(
                    model.energy(rij, orientationOf<Model, K>(bi), orientationOf<Model, K>(bj)));
            }
        deck.energyTerrace = potentialEnergyAllPairs(sys);
    }
    double deckEnergy = std::numeric_limits<double>::quiet_NaN();
    deck.tablePoints = refineTables(types.jobs, measure, deckEnergy, deck.notes);
    deck.energyDeck = measure ? deckEnergy : std::numeric_limits<double>::quiet_NaN();
    if (types.names.empty()) {
        deck.mapping.push_back(
            "g(r)·U_LJ(r) as pair_style table linear: " + std::to_string(deck.tablePoints) +
            " nodes uniform in r² on [" + shortNumber(types.jobs[0].table.rLow) + ", " +
            shortNumber(model.range()) + "] Å, terrace's U and F at each, in kcal/mol");
    } else {
        std::string list;
        for (int a = 0; a < nt; ++a)
            list += (a ? ", " : "") + types.names[a] + " as type " + std::to_string(a + 1) + " (" +
                    shortNumber(types.masses[a]) + " g/mol)";
        deck.mapping.push_back("species " + list);
        deck.mapping.push_back(
            "each pair of species' g(r)·U_LJ(r) with its own eps and sigma as pair_style table "
            "linear: " +
            std::to_string(deck.tablePoints) + " nodes uniform in r² up to " +
            (scene.potential.cutoff_per_pair ? "each pair's own r_u (at most " : "") +
            shortNumber(model.range()) + (scene.potential.cutoff_per_pair ? ")" : "") +
            " Å (tables TERRACE_LJ_<a>_<b>), terrace's U and F");
    }
    deck.mapping.push_back("equilibration: fix temp/rescale to " +
                           shortNumber(units::kelvin(scene.kT())) + " K every " +
                           std::to_string(t.thermostatEvery) + " steps for " +
                           std::to_string(t.equilibrate) + " steps, then NVE (fix nve) for " +
                           std::to_string(t.production) + " steps");
    if (types.names.empty()) {
        deck.table = "# Pair table written by `terrace export lammps`\n\n" +
                     tableSection(types.jobs[0].table, types.jobs[0].comment);
    } else {
        deck.table = "# Pair tables written by `terrace export lammps`\n\n";
        for (const TableJob& j : types.jobs)
            deck.table += tableSection(j.table, j.comment);
    }

    std::ostringstream data;
    data << dataHeader(scene, n, nt, L, "") << "Masses\n\n";
    for (int a = 0; a < nt; ++a)
        data << a + 1 << " " << number(types.masses[a]) << "\n";
    data << "\nAtoms # atomic\n\n";
    for (int i = 0; i < n; ++i)
        data << i + 1 << " " << typeOf(sys.bodies[i]) + 1 << " " << placed(sys.bodies[i].r, L)
             << "\n";
    data << "\nVelocities\n\n";
    for (int i = 0; i < n; ++i)
        data << i + 1 << " " << vec(sys.bodies[i].v * perFs) << "\n";
    deck.data = data.str();

    std::ostringstream in;
    in << deckHeader(scene, deck, t) << "atom_style      atomic\nread_data       data.lammps\n"
       << "pair_style      table linear " << deck.tablePoints << "\n";
    for (int a = 0; a < nt; ++a)
        for (int b = a; b < nt; ++b)
            in << "pair_coeff      " << a + 1 << " " << b + 1 << " pair.table "
               << types.jobs[types.jobOf[a][b]].key << " "
               << number(types.jobs[types.jobOf[a][b]].model.range()) << "\n";
    in << "neighbor        " << number(t.skinAngstrom) << " bin\n"
       << deckRun(t, "fix             nve all nve\n", true, units::kelvin(scene.kT()));
    deck.input = in.str();
    return deck;
}

// ---- Gay–Berne ellipsoids -----------------------------------------------------------------------

LammpsDeck gayBerneDeck(const Scene& scene) {
    LammpsDeck deck;
    const GayBernePotential gb = gayBernePotential(scene);
    const Smoothed<GayBernePotential> model{gb, sceneCutoff(scene)};
    const auto sys = buildInitialState<LinearRotor>(scene, model);
    const double L = sys.box.length, cut = model.range();
    refuseSmallBox(L, cut, "the cutoff r_u");
    const Timing t = timing(scene, deck.notes);
    const int n = sys.size();
    deck.atoms = n;

    // LAMMPS's ellipsoid: shape (diameters) σ0, σ0, κσ0 along its body x, y, z, the long axis z
    // as terrace's; its mass comes from a density, its inertia from the shape (uniform solid).
    const double a = 0.5 * gb.sigma, c = 0.5 * gb.kappa * gb.sigma; // radii
    const double volume = 4.0 / 3.0 * std::acos(-1.0) * a * a * c;
    const double m = sys.body.mass;
    const double inertiaLammps = m * (a * a + c * c) / 5.0; // about a transverse axis
    const double spinLammps = m * (2.0 * a * a) / 5.0;      // about the long axis
    const double eic = gb.mu > 0.0 ? 1.0 / gb.kappaPrime : 1.0;
    deck.mapping.push_back(
        "Gay-Berne as pair_style gayberne with gamma = 1 (U of r - sigma + sigma0), upsilon = nu "
        "= " +
        shortNumber(gb.nu) + ", mu = " + shortNumber(gb.mu) +
        ", eps = eps0 = " + shortNumber(gb.epsilon * kcalPerKj) + " kcal/mol, sigma = sigma0 = " +
        shortNumber(gb.sigma) + " Å, relative well depths (1, 1, " + shortNumber(eic) +
        "), shape (" + shortNumber(2 * a) + ", " + shortNumber(2 * a) + ", " + shortNumber(2 * c) +
        ") Å: terrace's U term for term (docs/LAMMPS.md)");
    deck.mapping.push_back("orientations as quaternions taking the body z axis to each "
                           "ellipsoid's axis; angular momenta I ω with LAMMPS's moment I");

    deck.notes.push_back("cutoff: terrace switches U off smoothly on [r_l, r_u] = [" +
                         shortNumber(model.cut.inner()) + ", " + shortNumber(cut) +
                         "] Å (g(r)·U); pair_style gayberne has no switch and cuts U at r_u");
    if (std::abs(inertiaLammps - sys.body.inertia[0]) > 1e-9 * sys.body.inertia[0])
        deck.notes.push_back("body.inertia: LAMMPS takes an ellipsoid's moment across its axis "
                             "from its mass and shape (uniform solid: " +
                             shortNumber(inertiaLammps) + " g/mol Å², the scene's is " +
                             shortNumber(sys.body.inertia[0]) +
                             "); the deck gives each ellipsoid terrace's angular velocity, so its "
                             "rotational kinetic energy differs by their ratio");
    deck.notes.push_back("rotation: terrace's linear rotor has no spin about its axis (2 "
                         "rotational degrees of freedom), LAMMPS's ellipsoid 3, with a moment of " +
                         shortNumber(spinLammps) +
                         " g/mol Å² about the axis (spin starts at 0; the temperature "
                         "temp/asphere reports counts it)");
    deck.notes.push_back("equilibration: terrace's velocity rescaling (run.equilibrate_ps) is not "
                         "in the deck; it runs NVE from the initial state");
    deck.notes.push_back("integrator: fix nve/asphere (LAMMPS's rotational update) in place of "
                         "terrace's exact free rotation of the linear rotor");

    deck.energyTerrace = deck.energyDeck = std::numeric_limits<double>::quiet_NaN();
    if (measured(n)) {
        double terrace = 0.0, lammps = 0.0;
        for (int i = 0; i < n; ++i)
            for (int j = i + 1; j < n; ++j) {
                const Vec3 rij = sys.box.minimumImage(sys.bodies[i].r - sys.bodies[j].r);
                if (rij.squaredNorm() >= cut * cut) continue;
                terrace += model.energy(rij, sys.bodies[i].s, sys.bodies[j].s);
                lammps += gb.energy(rij, sys.bodies[i].s, sys.bodies[j].s);
            }
        deck.energyTerrace = terrace;
        deck.energyDeck = lammps;
    }

    std::ostringstream data;
    data << dataHeader(scene, n, 1, L, (std::to_string(n) + " ellipsoids\n").c_str())
         << "Atoms # ellipsoid\n\n";
    for (int i = 0; i < n; ++i)
        data << i + 1 << " 1 1 " << number(m / volume) << " " << placed(sys.bodies[i].r, L) << "\n";
    data << "\nEllipsoids\n\n";
    for (int i = 0; i < n; ++i) {
        const Quat q = Quat::FromTwoVectors(Vec3::UnitZ(), sys.bodies[i].s);
        data << i + 1 << " " << number(2 * a) << " " << number(2 * a) << " " << number(2 * c) << " "
             << number(q.w()) << " " << number(q.x()) << " " << number(q.y()) << " "
             << number(q.z()) << "\n";
    }
    data << "\nVelocities\n\n";
    for (int i = 0; i < n; ++i)
        data << i + 1 << " " << vec(sys.bodies[i].v * perFs) << " "
             << vec(inertiaLammps * sys.bodies[i].w * perFs) << "\n";
    deck.data = data.str();

    std::ostringstream in;
    in << deckHeader(scene, deck, t) << "atom_style      ellipsoid\nread_data       data.lammps\n"
       << "# terrace's Gay-Berne (core/gay_berne_potential.hpp) is LAMMPS's with gamma = 1 (the\n"
       << "# shifted form x = r - sigma + sigma0), upsilon = nu, mu = mu, eps = eps0, sigma = "
          "sigma0,\n"
       << "# relative well depths (1, 1, 1/kappa') and shape (sigma0, sigma0, kappa sigma0).\n"
       << "pair_style      gayberne 1.0 " << number(gb.nu) << " " << number(gb.mu) << " "
       << number(cut) << "\n"
       << "pair_coeff      1 1 " << number(gb.epsilon * kcalPerKj) << " " << number(gb.sigma)
       << " 1 1 " << number(eic) << " 1 1 " << number(eic) << "\n"
       << "neighbor        " << number(t.skinAngstrom) << " bin\n"
       << "compute         rotational all temp/asphere\n"
       << deckRun(t, "fix             nve all nve/asphere\nthermo_modify   temp rotational\n",
                  false, 0.0);
    deck.input = in.str();
    return deck;
}

// ---- rigid site molecules -----------------------------------------------------------------------

template <BodyKind K, AttitudeUse use> LammpsDeck sitesDeck(const Scene& scene) {
    LammpsDeck deck;
    const std::vector<Site> sites = sceneSites(scene);
    const auto bare = SitePotential<use>::fromSites(sites);
    const SmoothedCutoff cut = sceneCutoff(scene);
    const Smoothed<SitePotential<use>> model{bare, cut};
    const auto sys = buildInitialState<K>(scene, model);
    const double L = sys.box.length;
    refuseSmallBox(L, cut.outer(), "the cutoff r_u");
    const Timing t = timing(scene, deck.notes);
    const int n = sys.size(), ns = static_cast<int>(sites.size());
    deck.atoms = n * ns;
    for (int a = 0; a < ns; ++a)
        if (!(sites[a].mass > 0.0))
            throw LammpsRefusal("body.sites[" + std::to_string(a) +
                                "].mass: a massless site has no LAMMPS atom (every atom of a "
                                "rigid body needs a mass > 0)");
    deck.notes.push_back(
        "cutoff: terrace switches a pair of molecules off by their centre distance R, g(R)·Σ U_ab; "
        "LAMMPS has no switch on a molecule's centre, so the deck switches each site pair by its "
        "own distance, Σ g(d_ab)·U_ab (the same g on [" +
        shortNumber(cut.inner()) + ", " + shortNumber(cut.outer()) +
        "] Å): the two differ for pairs near the "
        "cutoff");
    deck.notes.push_back("equilibration: terrace's velocity rescaling (run.equilibrate_ps) is not "
                         "in the deck; it runs NVE from the initial state");
    deck.notes.push_back("integrator: fix rigid/small (LAMMPS's NVE update of rigid bodies, the "
                         "quaternion by Richardson iteration) in place of terrace's exact free "
                         "rotation");

    // Site types: one per site; tables for every type pair a ≤ b.
    std::vector<TableJob> jobs;
    std::vector<std::vector<int>> jobOf(ns, std::vector<int>(ns));
    for (int a = 0; a < ns; ++a)
        for (int b = a; b < ns; ++b) {
            TableJob j;
            j.key = "SITES_" + std::to_string(a + 1) + "_" + std::to_string(b + 1);
            const LJPotential lj{bare.mixedEpsilon(a, b), bare.mixedSigma(a, b)};
            j.model = Smoothed<LJPotential>{lj, cut};
            j.sigma = lj.sigma;
            j.comment = "sites " + std::to_string(a + 1) + " and " + std::to_string(b + 1) +
                        ": g(d)·U_LJ(d), eps = " + number(lj.epsilon) +
                        " kJ/mol, sigma = " + number(lj.sigma) +
                        " Å (Lorentz-Berthelot); r (Å), U (kcal/mol), F";
            jobOf[a][b] = jobOf[b][a] = static_cast<int>(jobs.size());
            jobs.push_back(std::move(j));
        }
    // The sites in the lab: the body's centre plus its offset, as terrace's potential places them.
    std::vector<Vec3> at(static_cast<std::size_t>(n) * ns);
    for (int i = 0; i < n; ++i) {
        const auto o = orientationOf<SitePotential<use>, K>(sys.bodies[i]);
        for (int a = 0; a < ns; ++a)
            at[i * ns + a] = sys.bodies[i].r + siteOffset(o, sites[a].r);
    }
    const bool measure = measured(n);
    deck.energyTerrace = deck.energyDeck = std::numeric_limits<double>::quiet_NaN();
    if (measure) {
        const double cut2 = cut.outer() * cut.outer();
        for (int i = 0; i < n; ++i)
            for (int j = i + 1; j < n; ++j)
                for (int a = 0; a < ns; ++a)
                    for (int b = 0; b < ns; ++b) {
                        const Vec3 d = sys.box.minimumImage(at[i * ns + a] - at[j * ns + b]);
                        const double rsq = d.squaredNorm();
                        if (rsq >= cut2) continue;
                        TableJob& job = jobs[jobOf[a][b]];
                        job.pairs.rsq.push_back(rsq);
                        job.pairs.exact.push_back(job.model.energy(d, Vec3(), Vec3()));
                    }
        deck.energyTerrace = potentialEnergyAllPairs(sys);
    }
    double deckEnergy = 0.0;
    deck.tablePoints = refineTables(jobs, measure, deckEnergy, deck.notes);
    if (measure) deck.energyDeck = deckEnergy;
    deck.mapping.push_back(std::to_string(ns) +
                           " sites a molecule, each an atom of its own type, "
                           "the molecule a body of fix rigid/small; site velocities v + ω × d");
    deck.mapping.push_back(
        std::to_string(jobs.size()) + " site-pair tables (Lorentz-Berthelot) of g(d)·U_LJ(d), " +
        std::to_string(deck.tablePoints) + " nodes uniform in r²; intramolecular pairs excluded");
    deck.table = "# Pair tables written by `terrace export lammps`\n\n";
    for (const TableJob& j : jobs)
        deck.table += tableSection(j.table, j.comment);

    std::ostringstream data;
    data << dataHeader(scene, n * ns, ns, L, "") << "Masses\n\n";
    for (int a = 0; a < ns; ++a)
        data << a + 1 << " " << number(sites[a].mass) << "\n";
    data << "\nAtoms # molecular\n\n";
    for (int i = 0; i < n; ++i)
        for (int a = 0; a < ns; ++a)
            data << i * ns + a + 1 << " " << i + 1 << " " << a + 1 << " "
                 << placed(at[i * ns + a], L) << "\n";
    // A site moves with its body: v + ω × d; fix rigid/small takes the body's velocity and
    // angular momentum from these.
    data << "\nVelocities\n\n";
    for (int i = 0; i < n; ++i) {
        const Vec3 w = K::angularVelocity(sys.bodies[i], sys.body);
        for (int a = 0; a < ns; ++a) {
            const Vec3 d = at[i * ns + a] - sys.bodies[i].r;
            data << i * ns + a + 1 << " " << vec((sys.bodies[i].v + w.cross(d)) * perFs) << "\n";
        }
    }
    deck.data = data.str();

    std::ostringstream in;
    in << deckHeader(scene, deck, t) << "atom_style      molecular\nread_data       data.lammps\n"
       << "pair_style      table linear " << deck.tablePoints << "\n";
    for (int a = 0; a < ns; ++a)
        for (int b = a; b < ns; ++b)
            in << "pair_coeff      " << a + 1 << " " << b + 1 << " pair.table "
               << jobs[jobOf[a][b]].key << " " << number(cut.outer()) << "\n";
    in << "neighbor        " << number(t.skinAngstrom) << " bin\n"
       << "neigh_modify    exclude molecule/intra all\n"
       << deckRun(t, "fix             rigid all rigid/small molecule\n", false, 0.0);
    deck.input = in.str();
    return deck;
}

} // namespace

LammpsDeck lammpsDeck(const Scene& scene) {
    const std::string& kind = scene.potential.kind;
    if (kind == "lj" && !scene.species.empty())
        return sphereDeck<SpeciesSphere>(scene,
                                         Smoothed<LJMixture>{ljMixture(scene), sceneCutoff(scene)});
    if (kind == "lj")
        return sphereDeck<Sphere>(scene,
                                  Smoothed<LJPotential>{ljPotential(scene), sceneCutoff(scene)});
    if (kind == "gay-berne") return gayBerneDeck(scene);
    if (kind == "steps")
        throw LammpsRefusal("potential.kind: steps (a step table) has no LAMMPS equivalent: its "
                            "forces are impulses at the steps' radii, which time-stepped MD "
                            "cannot integrate");
    if (kind == "sites") {
        if (scene.body.kind == "linear") return sitesDeck<LinearRotor, AttitudeUse::Axis>(scene);
        return sitesDeck<AsymmetricTop, AttitudeUse::Frame>(scene);
    }
    throw LammpsRefusal("potential.kind: " + kind +
                        " (the paper's rod potential, core/rod_potential.hpp) has no LAMMPS pair "
                        "style: its U is LJ of r + ζ(1/2 − (s_i·s_j)²), which depends on the two "
                        "axes' angle, and no built-in style takes that form");
}

} // namespace terrace::cli
