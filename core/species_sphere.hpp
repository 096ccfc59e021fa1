#pragma once
// A sphere of one of a scene's species (Scene::species): translation only, like Sphere, and an
// index that a species potential reads to pick the pair's parameters (core/lj_mixture.hpp). The
// species of a body never changes. Every species has the scene's one mass (body.mass).
#include "core/body_kind.hpp"
#include <cstdint>

namespace terrace {

struct SpeciesSphere {
    static constexpr std::string_view name = "sphere";
    static constexpr int rotationalDof = 0;

    struct State {
        Vec3 r = Vec3::Zero();
        Vec3 v = Vec3::Zero();
        std::int32_t species = 0; // index into Scene::species
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
