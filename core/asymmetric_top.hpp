#pragma once
// Asymmetric top (I1, I2, I3 distinct): exact free motion in Jacobi elliptic functions and a
// theta-function series for the angle about L (van Zon & Schofield, J. Comput. Phys. 225, 145
// (2007); REFERENCES.md "Exact free rigid-body motion", steps 1-5).
#include "core/top_state.hpp"

namespace terrace {

struct AsymmetricTop : TopCommon {
    static constexpr std::string_view name = "asymmetric";
    static constexpr int rotationalDof = 3;

    /// Exact torque-free rotation over time t (any sign). Implemented in asymmetric_top.cpp.
    static void freeRotate(State& b, const BodyParams& p, double t);
};

} // namespace terrace
