#pragma once
// The continuous model's potential energy and pressure on the configurations of a run
// (experiments/convergence.sh): for each frame of DIR/trajectory.xyz, with the smoothed model of
// DIR/scene.json (core/smoothed_potential.hpp, potential.cutoff, whatever dmd.model the run used),
//     U = Σ_{i<j} U_s(r_ij, s_i, s_j),   W = Σ_{i<j} r_ij·F_ij,   P = (2 K_trans + W)/(3V)
// (core/pressure.hpp: the molecular virial, Allen & Tildesley sec. 2.4), all pairs, minimum image.
// On SMD's frames these are the engine's own U and P; on DMD's frames they measure how far the
// terraced dynamics' configurations are from the continuous model's, apart from the terracing of
// the observable itself (DMD's own energy is the terraced V, its pressure the impulse virial).
// Units: U per body in kJ/mol; P reduced, P* = Pσ³/ε.
#include <filesystem>

namespace terrace::experiments {

struct Configurational {
    int frames = 0;
    double potentialPerBody = 0.0; // ⟨U⟩/N over the frames, kJ/mol
    double pressureReduced = 0.0;  // ⟨P⟩σ³/ε over the frames
};

/// Averages over every whole frame of DIR/trajectory.xyz (rods: rod-lj, spheres: lj). Throws
/// std::runtime_error when DIR has no trajectory or scene, or the trajectory has no frame.
Configurational configurational(const std::filesystem::path& dir);

} // namespace terrace::experiments
