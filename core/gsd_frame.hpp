#pragma once
// Trajectory frames in GSD's HOOMD schema (version 1.4), so that OVITO, freud and gsd read them
// and a viewer draws each body as its shape. Per frame: configuration/step (the sample number),
// particles/position (wrapped into the box, centred on the origin as HOOMD's box is) with
// particles/image (unwrapped = position + image·L), particles/orientation (body -> lab quaternion,
// s x y z; a linear rotor's rotation of least angle taking the body z axis to its axis),
// particles/velocity, particles/angmom (HOOMD's conjugate quaternion momentum 2 q ⊗ (0, L_body))
// and log/time_ps. Frame 0 also holds what does not change: the box, N, one type named after the
// scene's body, typeid, mass, moment_inertia and type_shapes. Units are terrace's: Å, ps, g/mol,
// so velocity in Å/ps and angular momentum in g/mol Å²/ps.
#include "core/gsd_file.hpp"
#include "core/scene.hpp"
#include "core/snapshot.hpp"
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace terrace {

/// The chunk names a terrace GSD trajectory holds, in the order of their ids.
std::vector<std::string> hoomdChunkNames();

/// The shape a viewer draws for the scene's bodies, as GSD's shape specification (a JSON object):
/// Sphere (σ) for LJ spheres, Ellipsoid (σ_s/2, σ_s/2, κσ_s/2) for Gay–Berne, a spherocylinder
/// (ConvexPolyhedron of two vertices ±ζ/2 on the axis, rounded by σ/2: a picture of the rod-lj
/// model's reach, which is not a hard shape) for rods, and a SphereUnion of the sites (diameter σ
/// each) for site molecules.
nlohmann::json gsdTypeShape(const Scene& scene);

/// What frame 0 records of the bodies besides their state.
struct GsdBodyType {
    std::string name;      // e.g. "rod"
    nlohmann::json shape;  // gsdTypeShape
    double mass = 0.0;     // g/mol
    Vec3 inertia{0, 0, 0}; // principal moments, g/mol Å²
    // A mixture's species (Scene::species), each a type of its own named as the species, with
    // its own shape (a sphere of its σ; among rods, a rod species the rods' shape at its σ) and
    // mass; the bodies' typeid and mass (and among rods their moments of inertia, 0 for a
    // sphere) then come from the first frame's Snapshot::species.
    std::vector<std::string> species;
    std::vector<nlohmann::json> speciesShapes;
    std::vector<double> speciesMasses; // g/mol
    std::vector<Vec3> speciesInertia;  // g/mol Å²; empty: every body has `inertia`
};
GsdBodyType gsdBodyType(const Scene& scene);

/// Writes frame `sample` of the trajectory (time in internal units, box in Å) and, when it is the
/// file's first frame, the constant chunks. The bodies come piece by piece from
/// bodiesOf(begin, end), a snapshot of bodies begin … end−1 alone (as Snapshot holds them:
/// velocities per internal time unit), once for each per-body chunk: a frame of 10⁶ bodies is
/// never held whole.
void writeHoomdFrame(GsdWriter& file, int bodies, double time, double boxLength,
                     const std::function<Snapshot(int, int)>& bodiesOf, const GsdBodyType& type,
                     std::uint64_t sample, int bodiesPerPiece = 16384);
/// The same for a snapshot held whole.
void writeHoomdFrame(GsdWriter& file, const Snapshot& s, const GsdBodyType& type,
                     std::uint64_t sample);

/// Every frame of a GSD trajectory this program wrote, handed to `each` one at a time as a
/// snapshot (unwrapped positions; velocities and angular velocities per internal time unit; the
/// axis, and for bodies with three moments the orientation); returns the number of frames. The
/// values are GSD's single precision. Throws TrajectoryError naming the file and what is missing.
long forEachGsdFrame(const std::filesystem::path& path,
                     const std::function<void(Snapshot&&)>& each);

} // namespace terrace
