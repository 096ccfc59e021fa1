#pragma once
// SMD run parameters read from a scene's "smd" block and checked before any work (DESIGN.md "Bad
// input"): time step dt (fs in the scene, time units here) and Verlet skin (σ in the scene, Å
// here). The cutoff r_u is the model's (potential.cutoff, core/smoothed_potential.hpp). The box
// must hold two cutoffs plus skins, L >= 2 (r_u + skin), so that a pair within reach has exactly
// one periodic image within reach.
#include "core/scene.hpp"
#include "core/units.hpp"
#include <cmath>
#include <sstream>
#include <string>

namespace terrace::smd {

struct Parameters {
    double dt = 0.0;   // time units (100 fs)
    double skin = 0.0; // Å
};

namespace detail {

inline std::string show(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
}

} // namespace detail

/// Validated SMD parameters for a box of edge boxLength (Å) and a model of range r_u (Å); throws
/// SceneError naming the key.
inline Parameters parameters(const Scene& scene, double boxLength, double range) {
    const Scene::Smd& s = scene.smd;
    const double sigma = scene.potential.sigma;
    using detail::show;
    if (!(std::isfinite(s.dt_fs) && s.dt_fs > 0.0))
        throw SceneError("smd.dt_fs: must be > 0 (got " + show(s.dt_fs) + ")");
    if (!(std::isfinite(s.skin) && s.skin >= 0.0))
        throw SceneError("smd.skin: must be >= 0 (got " + show(s.skin) + ")");
    if (!std::isfinite(range))
        throw SceneError("potential.cutoff: SMD needs a finite cutoff (the model has none)");
    if (!(std::isfinite(sigma) && sigma > 0.0))
        throw SceneError("potential.sigma: must be > 0 (got " + show(sigma) + ")");
    Parameters p;
    p.dt = units::fromFs(s.dt_fs);
    p.skin = s.skin * sigma;
    const double needed = 2.0 * (range + p.skin);
    if (!(boxLength >= needed))
        throw SceneError("potential.cutoff: the box edge " + show(boxLength) +
                         " Å is shorter than 2·(r_u + skin) = " + show(needed) +
                         " Å; use more bodies, a lower density, or a smaller r_u or smd.skin");
    return p;
}

} // namespace terrace::smd
