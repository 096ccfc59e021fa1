#pragma once
// SMD run parameters read from a scene's "smd" block and checked before any work (DESIGN.md "Bad
// input"): time step dt (fs in the scene, time units here), Verlet skin and the smoothed cutoff
// r_l < r_u (units of σ in the scene, Å here). The box must hold two cutoffs plus skins,
// L >= 2 (r_u + skin), so that a pair within reach has exactly one periodic image within reach.
#include "core/scene.hpp"
#include "core/units.hpp"
#include "smd/smoothed_cutoff.hpp"
#include <cmath>
#include <sstream>
#include <string>

namespace terrace::smd {

struct Parameters {
    double dt = 0.0;   // time units (100 fs)
    double skin = 0.0; // Å
    SmoothedCutoff cutoff;
};

namespace detail {

inline std::string show(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
}

} // namespace detail

/// Validated SMD parameters for a box of edge boxLength (Å); throws SceneError naming the key.
inline Parameters parameters(const Scene& scene, double boxLength) {
    const Scene::Smd& s = scene.smd;
    const double sigma = scene.potential.sigma;
    using detail::show;
    if (!(std::isfinite(s.dt_fs) && s.dt_fs > 0.0))
        throw SceneError("smd.dt_fs: must be > 0 (got " + show(s.dt_fs) + ")");
    if (!(std::isfinite(s.skin) && s.skin >= 0.0))
        throw SceneError("smd.skin: must be >= 0 (got " + show(s.skin) + ")");
    if (!(std::isfinite(s.r_l) && s.r_l > 0.0))
        throw SceneError("smd.r_l: must be > 0 (got " + show(s.r_l) + ")");
    if (!(std::isfinite(s.r_u) && s.r_u > s.r_l))
        throw SceneError("smd.r_u: must be > smd.r_l = " + show(s.r_l) + " (got " + show(s.r_u) +
                         ")");
    if (!(std::isfinite(sigma) && sigma > 0.0))
        throw SceneError("potential.sigma: must be > 0 (got " + show(sigma) + ")");
    Parameters p;
    p.dt = units::fromFs(s.dt_fs);
    p.skin = s.skin * sigma;
    p.cutoff = {s.r_l * sigma, s.r_u * sigma};
    const double needed = 2.0 * (p.cutoff.outer() + p.skin);
    if (!(boxLength >= needed))
        throw SceneError("smd.r_u: the box edge " + show(boxLength) +
                         " Å is shorter than 2·(r_u + skin) = " + show(needed) +
                         " Å; use more bodies, a lower density, or a smaller smd.r_u/smd.skin");
    return p;
}

} // namespace terrace::smd
