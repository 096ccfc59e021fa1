#pragma once
// `terrace export lammps`: a scene's model and initial state as a LAMMPS data file, input deck
// and pair table (the text of each, built here without touching the disk, so that tests read
// it). What LAMMPS has is mapped; what it lacks is refused (LammpsRefusal) or, where the deck can
// come close, written with a note naming every difference:
//   lj        spheres, atom_style atomic; the smoothed g(r)·U_LJ that SMD integrates as a
//             pair_style table linear of its exact U and F, fine enough that the table's
//             interpolation moves the first frame's U by at most tableTolerance (measured here);
//             a mixture's species each an atom type with its mass, each pair of species a table
//             of its own ε and σ on the one smoothed cutoff.
//   gay-berne ellipsoids, atom_style ellipsoid, pair_style gayberne with γ = 1, υ = ν, μ, shape
//             (σ0, σ0, κσ0) and relative well depths (1, 1, 1/κ'): LAMMPS's form is then terrace's
//             U term for term; its cutoff is a plain cut at r_u (no switch), fix nve/asphere.
//   sites     every site an atom of its own type, molecules held by fix rigid/small molecule,
//             site pairs through tables of g(d)·U_LJ(d) with the switch on the site distance d
//             (LAMMPS has none on the molecules' centre distance, where terrace's acts).
//   rod-lj    refused: no LAMMPS pair style has the rod potential.
// Units: LAMMPS real (Å, g/mol, fs, kcal/mol, K): energies /4.184, velocities Å/ps → Å/fs.
#include "cli/lammps_table.hpp"
#include "core/scene.hpp"
#include <stdexcept>
#include <string>
#include <vector>

namespace terrace::cli {

/// What LAMMPS cannot represent: one line naming the scene key and the reason.
class LammpsRefusal : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct LammpsDeck {
    std::string data;                 // data.lammps: box, masses, atoms, velocities (+ ellipsoids)
    std::string input;                // in.terrace: the input deck
    std::string table;                // pair.table ("" when the deck needs none)
    std::vector<std::string> mapping; // one line per thing mapped, and how
    std::vector<std::string> notes;   // one line per difference between the deck and terrace
    int atoms = 0;
    int tablePoints = 0; // nodes per table (0: no table)
    // The initial state's potential energy (kJ/mol): under terrace's model (g·U as SMD
    // integrates it) and under the deck's (as LAMMPS evaluates it, table interpolation
    // included); NaN when not measured (more bodies than measureLimit).
    double energyTerrace = 0.0;
    double energyDeck = 0.0;
};

/// Above this many bodies the first-frame energies are not measured (an O(N²) pass) and the
/// table takes defaultTablePoints.
inline constexpr int measureLimit = 20000;
inline constexpr int defaultTablePoints = 1 << 17;
/// The tables are refined (doubling from minTablePoints) until the interpolation moves the first
/// frame's U by at most this, relative; maxTablePoints bounds the file (~18 MB a table). Linear
/// interpolation in r² needs many: 65 536 points leave 5.5e-7 on 256 LJ spheres at ρ* = 0.8, 131
/// 072 1.2e-7.
inline constexpr double tableTolerance = 2.5e-7;
inline constexpr int minTablePoints = 4096;
inline constexpr int maxTablePoints = 1 << 18;

/// The deck of a resolved scene (cli::resolveScene). Throws LammpsRefusal for what LAMMPS cannot
/// represent, SceneError for a scene whose initial state cannot be built.
LammpsDeck lammpsDeck(const Scene& scene);

} // namespace terrace::cli
