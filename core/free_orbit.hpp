#pragma once
// A body's free orbit prepared once from a State, for searches that ask for its orientation at
// many times τ (the DMD pair search): axis(τ) and ω(τ) of the exact torque-free motion, equal to
// freeMove<K> over τ from the same State. Translation, r(τ) = r + v τ, is left to the caller.
//
// Linear rotor (REFERENCES.md "Exact free rigid-body motion"; DESIGN.md "Rigid bodies"):
//     s(τ) = s cos(|ω|τ) + (ω̂ × s) sin(|ω|τ),   ω constant,
// with |ω| and ω̂ × s computed once here instead of at every τ. The expression and its
// normalisation are those of LinearRotor::freeRotate, term for term, so the result is the same
// to the last bit. Spheres have a fixed axis and no rotation. Other kinds keep the State and call
// their own freeRotate at every τ: the exact motion stays written once, in the kind's header.
// Units: time unit 100 fs, ω in rad per time unit.
#include "core/body_kind.hpp"
#include "core/linear_rotor.hpp"
#include "core/sphere.hpp"
#include <cmath>

namespace terrace {

/// Any body kind: the State is rotated afresh at every τ.
template <BodyKind K> class FreeOrbit {
public:
    FreeOrbit(const typename K::State& start, const BodyParams& p) : start_(start), params_(&p) {}
    struct Attitude {
        Vec3 axis; // unit long (symmetry) axis
        Vec3 w;    // lab angular velocity
    };
    Attitude at(double tau) const {
        typename K::State b = start_;
        K::freeRotate(b, *params_, tau);
        return {K::axis(b), K::angularVelocity(b, *params_)};
    }

private:
    typename K::State start_;
    const BodyParams* params_;
};

/// Linear rotor: one sincos per τ; ω is constant.
template <> class FreeOrbit<LinearRotor> {
public:
    FreeOrbit(const LinearRotor::State& start, const BodyParams&)
        : s_(start.s), w_(start.w), speed_(start.w.norm()) {
        if (speed_ != 0.0) sideways_ = (start.w / speed_).cross(start.s);
    }
    struct Attitude {
        Vec3 axis;
        Vec3 w;
    };
    Attitude at(double tau) const {
        if (speed_ == 0.0) return {s_, w_};
        const double angle = speed_ * tau;
        const Vec3 s = s_ * std::cos(angle) + sideways_ * std::sin(angle);
        return {s / s.norm(), w_};
    }

private:
    Vec3 s_, w_;
    double speed_;
    Vec3 sideways_{0.0, 0.0, 0.0}; // ω̂ × s, the direction s turns towards
};

/// Sphere: nothing turns.
template <> class FreeOrbit<Sphere> {
public:
    FreeOrbit(const Sphere::State&, const BodyParams&) {}
    struct Attitude {
        Vec3 axis;
        Vec3 w;
    };
    Attitude at(double) const { return {Vec3::UnitZ(), Vec3::Zero()}; }
};

} // namespace terrace
