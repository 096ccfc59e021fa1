#pragma once
// A scene: everything that defines a run, read from JSON with every key validated. An unknown key,
// a wrong type or an out-of-range value is a SceneError naming the file and the dotted key; there
// are no silent defaults for keys that are present. Absent keys take the documented defaults,
// which are the paper's dense rods (DESIGN.md "The rod model").
#include "core/vec.hpp"
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace terrace {

class SceneError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// One body of an explicit initial configuration (state.particles).
struct ParticleSpec {
    Vec3 r = Vec3::Zero();           // Å
    Vec3 v = Vec3::Zero();           // Å/ps
    Vec3 axis = Vec3::UnitZ();       // unit long axis (linear rotors)
    std::optional<Quat> orientation; // body -> lab, tops ([w, x, y, z])
    Vec3 omega = Vec3::Zero();       // lab angular velocity, rad/ps
};

struct Scene {
    std::string name = "dense-rods";
    std::uint64_t seed = 1;

    struct Body {
        std::string kind = "linear";     // sphere | linear | symmetric | asymmetric
        double mass = 18.0;              // g/mol
        Vec3 inertia{1.154, 1.154, 0.0}; // g/mol Å², principal moments
    } body;

    struct Potential {
        std::string kind = "rod-lj"; // rod-lj | lj
        double epsilon = 3.0;        // kJ/mol
        double sigma = 3.035;        // Å
        double zeta = 1.0;           // Å (rod-lj only)
    } potential;

    struct State {
        int n = 512;
        double density = 0.5;                // ρσ³
        double temperature = 1.4;            // T* = kT/ε
        std::string orientations = "random"; // random | aligned (lattice starts only)
        std::vector<ParticleSpec> particles; // explicit start; overrides the lattice when given
    } state;

    std::string engine = "dmd"; // dmd | smd

    struct Dmd {
        double dV = 0.5;            // terrace height in units of kT
        std::vector<double> levels; // explicit levels U_k in kJ/mol (overrides dV when given)
        std::string queue = "bpq";  // heap | bpq
        std::string invalidation = "lazy"; // lazy | eager
        double horizon_fs = 4.0;           // virtual-event horizon and largest search step
    } dmd;

    struct Smd {
        double dt_fs = 1.8;
        double skin = 0.3; // Verlet skin, σ
        double r_l = 2.5;  // start of the smoothed cutoff, σ
        double r_u = 3.0;  // end of the smoothed cutoff, σ
    } smd;

    struct Run {
        double equilibrate_ps = 2.0;
        double time_ps = 10.0;
        double sample_fs = 9.0; // a whole number of SMD steps at dt = 0.2, 0.5, 1, 1.8 and 3 fs
    } run;

    struct Output {
        double trajectory_every_fs = 0.0; // 0 = no trajectory
    } output;

    double kT() const { return state.temperature * potential.epsilon; } // kJ/mol
    double boxLength() const;                                           // Å, from n and density
};

/// The built-in default scene: the paper's dense rods (N 512, ρ* 0.5, T* 1.4).
Scene defaultScene();

/// Parse and validate; `origin` names the source in error messages (a file path or "<default>").
/// `overrides` are "dotted.key=value" strings applied before validation (value parsed as JSON,
/// or taken as a string when it is not valid JSON).
Scene sceneFromJson(const nlohmann::json& j, const std::string& origin,
                    const std::vector<std::string>& overrides = {});
Scene loadScene(const std::string& path, const std::vector<std::string>& overrides = {});

/// The fully resolved scene, every key written out (recorded next to every run's output).
nlohmann::json toJson(const Scene& s);

} // namespace terrace
