#pragma once
// Point particle / sphere: translation only, no rotational degrees of freedom.
#include "core/body_kind.hpp"

namespace terrace {

struct Sphere {
    static constexpr std::string_view name = "sphere";
    static constexpr int rotationalDof = 0;

    struct State {
        Vec3 r = Vec3::Zero();
        Vec3 v = Vec3::Zero();
    };

    static void freeRotate(State&, const BodyParams&, double) {}
    static Vec3 axis(const State&) { return Vec3::UnitZ(); }
    static Vec3 angularVelocity(const State&, const BodyParams&) { return Vec3::Zero(); }
    static Vec3 angularMomentum(const State&, const BodyParams&) { return Vec3::Zero(); }
    static double rotationalKinetic(const State&, const BodyParams&) { return 0.0; }
    static double inverseInertia(const State&, const BodyParams&, const Vec3&, const Vec3&) {
        return 0.0;
    }
    static void addAngularMomentum(State&, const BodyParams&, const Vec3&) {}
    static void scaleAngularVelocity(State&, const BodyParams&, double) {}
};

} // namespace terrace
