#pragma once
// Trajectories as extended XYZ, readable by OVITO and ASE: one frame per block of N+2 lines,
//     N
//     Lattice="L 0 0 0 L 0 0 0 L" Properties=<columns> Time=<fs> pbc="T T T" units="..."
//     X <columns...> <body>
// Columns: rods        species:S:1:pos:R:3:velo:R:3:axis:R:3:omega:R:3:body:I:1
//          tops        species:S:1:pos:R:3:velo:R:3:orientation:R:4:omega:R:3:body:I:1
//                      (quaternion w x y z, body -> lab)
//          spheres     species:S:1:pos:R:3:velo:R:3:body:I:1
//          a mixture's bodies (Snapshot::species filled) add species_index:I:1, the body's index
//          into the scene's species (its scene.json names them)
// pos in Å (unwrapped centres of mass, so that displacements survive the round trip), velo in
// Å/ps, omega in rad/ps, Time in fs. Numbers are written with 17 significant digits: positions and
// axes read back bit for bit, velocities and times to within the round-off of the unit conversion.
// Readers take the species column for chemical elements (ASE fails on an unknown one), so every
// body is X, ASE's dummy element (atomic number 0; to OVITO a type name like any other), and its
// kind is the integer body column: its rotational degrees of freedom, 0 sphere, 2 rod (linear
// rotor), 3 top. An integer, because OVITO skips
// string columns other than the species; not "type", which OVITO takes for the species. ASE
// renames only species, pos, Z and charge; velo, axis, orientation, omega and body stay arrays of
// those names (OVITO maps velo, omega and orientation to Velocity, Angular Velocity and
// Orientation, whose quaternion it orders x y z w). species_index is an array of that name to ASE
// and an integer property to OVITO, which can colour or select by it; it is no chemical element
// for the reason above. readTrajectory also reads the files written
// before the body column (species S, R or T and no body column).
#include "core/snapshot.hpp"
#include <functional>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace terrace {

class TrajectoryError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

enum class TrajectoryLayout { Sphere, Rod, Top };

/// The layout a body kind is written with (by its rotational degrees of freedom).
constexpr TrajectoryLayout layoutFor(int rotationalDof) {
    return rotationalDof == 0
               ? TrajectoryLayout::Sphere
               : (rotationalDof == 2 ? TrajectoryLayout::Rod : TrajectoryLayout::Top);
}

void writeXyzFrame(std::ostream& out, const Snapshot& frame, TrajectoryLayout layout);
/// The frame as writeXyzFrame writes it, as one string: one record for an AppendFile.
std::string formatXyzFrame(const Snapshot& frame, TrajectoryLayout layout);
/// The same bytes for a frame of `bodies` bodies at `time` (time units) in a box of `boxLength`
/// (Å), handed to `sink` in pieces of at most `bodiesPerPiece` bodies (the header first), whose
/// bodies come piece by piece from bodiesOf(begin, end), a snapshot of bodies begin … end−1
/// alone: a frame of 10⁶ bodies (~0.3 GB of text) and its snapshot are never held whole.
void writeXyzFramePieces(int bodies, double time, double boxLength, TrajectoryLayout layout,
                         const std::function<Snapshot(int, int)>& bodiesOf,
                         const std::function<void(std::string_view)>& sink,
                         int bodiesPerPiece = 4096);

/// Every frame of an extended XYZ file written by writeXyzFrame. Throws TrajectoryError naming the
/// file and line on anything malformed. A last frame cut short by the end of the file (a run
/// killed while writing it) is dropped when `partialLastFrame` is given, which then says so
/// (empty when the file ends on a whole frame); without it, that too is an error.
std::vector<Snapshot> readTrajectory(const std::string& path,
                                     std::string* partialLastFrame = nullptr);

/// The same frames handed one at a time to `each` as they are read, so that a long trajectory
/// is never held whole (terrace analyse); returns the number of whole frames. The errors and
/// the cut-short last frame are as for readTrajectory; frames before an error have been handed on.
long forEachTrajectoryFrame(const std::string& path, const std::function<void(Snapshot&&)>& each,
                            std::string* partialLastFrame = nullptr);

} // namespace terrace
