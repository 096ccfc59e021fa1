#pragma once
// A body's free orbit prepared once from a State, for searches that ask for its orientation at
// many times τ (the DMD pair search): axis(τ) and ω(τ) of the exact torque-free motion, equal to
// freeMove<K> over τ from the same State. Translation, r(τ) = r + v τ, is left to the caller.
//
// Linear rotor (REFERENCES.md "Exact free rigid-body motion"; DESIGN.md "Rigid bodies"):
//     s(τ) = s cos(|ω|τ) + (ω̂ × s) sin(|ω|τ),   ω constant,
// with |ω| and ω̂ × s computed once here instead of at every τ: LinearRotor::freeRotate's
// expression, without its renormalisation, so the two agree to a few ulp. Spheres have a fixed axis
// and no rotation. Other kinds keep the State and call their own freeRotate at every τ: the exact
// motion stays written once, in the kind's header. from(τ₀) gives the same orbit seen from τ₀ on,
// so that a search sampling a few fs past "now" turns each body through small angles only (where
// the rotor's sin and cos come from a short series, core/small_angle.hpp).
// Units: time unit 100 fs, ω in rad per time unit.
#include "core/asymmetric_top.hpp"
#include "core/body_kind.hpp"
#include "core/linear_rotor.hpp"
#include "core/small_angle.hpp"
#include "core/species_rotor.hpp"
#include "core/species_sphere.hpp"
#include "core/sphere.hpp"
#include <array>
#include <cassert>
#include <cmath>
#include <type_traits>

namespace terrace {

/// Any body kind: the State is rotated afresh at every τ. The attitude carries the whole frame
/// where the kind has one (tops), for potentials that read more than the axis.
template <BodyKind K> class FreeOrbit {
    static constexpr bool framed = requires(const typename K::State& b) { K::frame(b); };

public:
    FreeOrbit(const typename K::State& start, const BodyParams& p) : start_(start), params_(&p) {}
    struct Empty {};
    struct Attitude {
        Vec3 axis; // unit long (symmetry) axis
        Vec3 w;    // lab angular velocity
        [[no_unique_address]] std::conditional_t<framed, Mat3, Empty> frame; // body -> lab
    };
    Attitude at(double tau) const {
        typename K::State b = start_;
        K::freeRotate(b, *params_, tau);
        if constexpr (framed)
            return {K::axis(b), K::angularVelocity(b, *params_), K::frame(b)};
        else
            return {K::axis(b), K::angularVelocity(b, *params_), {}};
    }
    FreeOrbit from(double tau0) const {
        FreeOrbit o = *this;
        if (tau0 != 0.0) K::freeRotate(o.start_, *params_, tau0);
        return o;
    }
    /// The attitude at τ₀, exactly as from(τ₀).at(0) gives it.
    Attitude startOf(double tau0) const { return from(tau0).at(0.0); }

private:
    typename K::State start_;
    const BodyParams* params_;
};

/// Both bodies of a pair at τ (the DMD search's sample): {i.at(τ), j.at(τ)}.
template <BodyKind K> auto attitudesAt(const FreeOrbit<K>& i, const FreeOrbit<K>& j, double tau) {
    return std::array{i.at(tau), j.at(tau)};
}

/// Linear rotor: one sincos per τ; ω is constant. A rotor of a mixture with spheres
/// (SpeciesRotor) carries its species in the attitude, which is what RodMixture reads besides the
/// axis; a sphere of it has ω = 0 and so a fixed axis.
template <BodyKind K>
requires isLinearRotorKind<K>
class FreeOrbit<K> {
    static constexpr bool withSpecies = std::is_same_v<K, SpeciesRotor>;
    struct NoSpecies {};
    using Species = std::conditional_t<withSpecies, int, NoSpecies>;

public:
    FreeOrbit(const typename K::State& start, const BodyParams&)
        : FreeOrbit(start, start.w.norm()) {}
    /// The same orbit, bit for bit, from a state whose |ω| is known (speed: start.w.norm()), as
    /// the DMD engine keeps it in a body's book: one division and a cross product, no root.
    FreeOrbit(const typename K::State& start, double speed)
        : s_(start.s), w_(start.w), speed_(speed) {
        if (speed_ != 0.0) sideways_ = (start.w * (1.0 / speed_)).cross(start.s);
        if constexpr (withSpecies) species_ = start.species;
    }
    struct Attitude {
        Vec3 axis;
        Vec3 w;
        [[no_unique_address]] Species species;
    };
    Attitude at(double tau) const {
        if (speed_ == 0.0) return {s_, w_, species_};
        // s and ω̂ × s are orthonormal to round-off, so |s(τ)| = 1 to a few ulp without the
        // renormalisation freeRotate applies to the State it keeps (where errors would build up).
        const SinCos turn = sinCos(speed_ * (shift_ + tau));
        return {s_ * turn.cos + sideways_ * turn.sin, w_, species_};
    }
    /// The attitude at τ₀ as from(τ₀).at(0) gives it, bit for bit, without building the shifted
    /// orbit: both take one sincos of |ω|(shift + τ₀), and at(0) of a turned orbit is its s
    /// (sin 0 = 0, cos 0 = 1 exactly).
    Attitude startOf(double tau0) const { return at(tau0); }
    /// Over a small angle the start is only shifted (the series in at() still serves); beyond
    /// it, the pair (s, ω̂ × s) is turned on by τ₀, one rotation of the plane they span.
    FreeOrbit from(double tau0) const {
        FreeOrbit o = *this;
        if (std::abs(speed_ * (shift_ + tau0)) <= shiftedAngle) {
            o.shift_ += tau0;
            return o;
        }
        const SinCos turn = sinCos(speed_ * (shift_ + tau0));
        o.s_ = s_ * turn.cos + sideways_ * turn.sin;
        o.sideways_ = sideways_ * turn.cos - s_ * turn.sin;
        o.shift_ = 0.0;
        return o;
    }

    /// The orbit re-based at τ₀ (s and ω̂ × s turned on by τ₀, no shift left), with s brought
    /// back to unit length: what a body in free flight keeps when it is brought to τ₀ (its s is
    /// then axis()). One sincos (a short series over the usual angles) and no square root of
    /// |ω|, where rebuilding the orbit from a freely rotated state takes three square roots, a
    /// division and the library's sincos.
    FreeOrbit advancedBy(double tau0) const {
        FreeOrbit o = *this;
        // A body that does not turn (a sphere among rods) keeps its axis to the bit: renormalised
        // at every flight, it would wander by an ulp at a time.
        if (speed_ == 0.0) {
            o.shift_ = 0.0;
            return o;
        }
        const SinCos turn = sinCos(speed_ * (shift_ + tau0));
        const Vec3 s = s_ * turn.cos + sideways_ * turn.sin;
        o.s_ = s / s.norm(); // as freeRotate: round-off must not build up over many flights
        o.sideways_ = sideways_ * turn.cos - s_ * turn.sin;
        o.shift_ = 0.0;
        return o;
    }
    /// The long axis where the orbit is based (after advancedBy: at τ₀).
    const Vec3& axis() const { return s_; }

    /// The pair's two sincos in one packed pass. A rotor at rest has speed 0 and a zero sideways
    /// vector, so its angle is 0 and its axis comes out as s exactly, without a branch.
    friend std::array<Attitude, 2> attitudesAt(const FreeOrbit& i, const FreeOrbit& j, double tau) {
        const auto turn = sinCosPair(i.speed_ * (i.shift_ + tau), j.speed_ * (j.shift_ + tau));
        return {Attitude{i.s_ * turn[0].cos + i.sideways_ * turn[0].sin, i.w_, i.species_},
                Attitude{j.s_ * turn[1].cos + j.sideways_ * turn[1].sin, j.w_, j.species_}};
    }

private:
    Vec3 s_, w_;
    double speed_;
    [[no_unique_address]] Species species_{};
    Vec3 sideways_{0.0, 0.0, 0.0}; // ω̂ × s, the direction s turns towards
    double shift_ = 0.0;           // from(): time since s_ and sideways_ were taken
    // A search samples up to a few fs past its start, i.e. ≲ 0.15 rad for the paper's rods: a
    // shift leaving that much room below the series limit π/4 saves a rotation per body.
    static constexpr double shiftedAngle = 0.5;
};

/// Asymmetric top: the free rotation prepared once (AsymmetricTop::FreeRotation: ordering,
/// elliptic parameter, theta or Legendre constants), so that a sample costs one evaluation of the
/// attitude instead of that preparation as well. The attitude at τ is the prepared rotation at
/// shift + τ, which is what freeRotate over the same time from the same State gives, bit for bit
/// (freeRotate builds the same FreeRotation and evaluates it there).
template <> class FreeOrbit<AsymmetricTop> {
public:
    FreeOrbit(const AsymmetricTop::State& start, const BodyParams& p)
        : rotation_(start, p), A0_(start.A), L_(start.L), params_(&p) {}
    struct Attitude {
        Vec3 axis;
        Vec3 w;
        Mat3 frame; // body -> lab
    };
    Attitude at(double tau) const {
        const double t = shift_ + tau;
        const Mat3 A = t == 0.0 ? A0_ : rotation_.attitude(t); // freeRotate leaves A at t = 0
        const Vec3 wBody = (A * L_).cwiseQuotient(params_->inertia);
        return {A.row(2).transpose(), A.transpose() * wBody, A.transpose()};
    }
    FreeOrbit from(double tau0) const {
        FreeOrbit o = *this;
        o.shift_ += tau0;
        return o;
    }
    Attitude startOf(double tau0) const { return at(tau0); }

private:
    AsymmetricTop::FreeRotation rotation_;
    Mat3 A0_;
    Vec3 L_; // lab angular momentum, constant in free flight
    const BodyParams* params_;
    double shift_ = 0.0; // from(): time since the prepared start
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
    FreeOrbit from(double) const { return *this; }
    Attitude startOf(double) const { return at(0.0); }
};

/// A sphere of a species: nothing turns; the attitude carries the species, which is all that a
/// species potential reads of a body (core/lj_mixture.hpp).
template <> class FreeOrbit<SpeciesSphere> {
public:
    FreeOrbit(const SpeciesSphere::State& b, const BodyParams&) : species_(b.species) {}
    struct Attitude {
        Vec3 axis;
        Vec3 w;
        int species;
    };
    Attitude at(double) const { return {Vec3::UnitZ(), Vec3::Zero(), species_}; }
    FreeOrbit from(double) const { return *this; }
    Attitude startOf(double) const { return at(0.0); }

private:
    int species_;
};

} // namespace terrace
