#pragma once
// One engine built from a scene exactly as `terrace run` builds a fresh run's (cli/dispatch.hpp),
// held behind an interface that forgets its (engine, body kind, potential) type, so that a caller
// (the Python module's terrace.Simulation) advances it and reads it without a run directory.
// Nothing is sampled, thermostatted or written unless the caller asks: this is the engine contract
// (core/engine.hpp) and no more. Units are the engines' own (Å, g/mol, kJ/mol, the 100 fs time
// unit). The factories live beside runDmd and runSmd (run_dmd.cpp, run_smd.cpp), so that each
// engine type is instantiated once for both.
#include "core/continuous_sums.hpp"
#include "core/engine.hpp"
#include "core/pressure.hpp"
#include "core/scene.hpp"
#include "core/snapshot.hpp"
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

namespace terrace::cli {

class EngineHandle {
public:
    virtual ~EngineHandle() = default;
    virtual void advanceTo(double t) = 0;
    virtual double time() const = 0;
    virtual Snapshot snapshot() const = 0;
    virtual Snapshot positions() const = 0;
    virtual double kineticEnergy() const = 0;
    virtual double translationalKineticEnergy() const = 0;
    virtual double potentialEnergy() const = 0;
    virtual ContinuousSums continuousSums() const = 0;
    virtual VirialKind virialKind() const = 0;
    virtual double virial() const = 0;
    virtual Vec3 totalMomentum() const = 0;
    virtual void rescaleTemperature(double kT) = 0;
    virtual nlohmann::json statistics() const = 0;
    /// Of the instantaneous temperature: 3 per body, plus each body's rotational ones, less the
    /// total momentum's 3 (core/system.hpp degreesOfFreedom).
    virtual int degreesOfFreedom() const = 0;
};

/// The engine E behind the interface, its system's degrees of freedom counted when it was built
/// (a body's never change).
template <Engine E> class EngineHandleOf final : public EngineHandle {
public:
    EngineHandleOf(std::unique_ptr<E> engine, int degreesOfFreedom)
        : engine_(std::move(engine)), degreesOfFreedom_(degreesOfFreedom) {}
    void advanceTo(double t) override { engine_->advanceTo(t); }
    double time() const override { return engine_->time(); }
    Snapshot snapshot() const override { return engine_->snapshot(); }
    Snapshot positions() const override { return engine_->positions(); }
    double kineticEnergy() const override { return engine_->kineticEnergy(); }
    double translationalKineticEnergy() const override {
        return engine_->translationalKineticEnergy();
    }
    double potentialEnergy() const override { return engine_->potentialEnergy(); }
    ContinuousSums continuousSums() const override { return engine_->continuousSums(nullptr); }
    VirialKind virialKind() const override { return E::virialKind; }
    double virial() const override { return engine_->virial(); }
    Vec3 totalMomentum() const override { return engine_->totalMomentum(); }
    void rescaleTemperature(double kT) override { engine_->rescaleTemperature(kT); }
    nlohmann::json statistics() const override { return engine_->statistics(); }
    int degreesOfFreedom() const override { return degreesOfFreedom_; }

private:
    std::unique_ptr<E> engine_;
    int degreesOfFreedom_;
};

/// The scene's engine (scene.engine) on the scene's initial state; the scene must be resolved
/// (resolveEngineSections).
std::unique_ptr<EngineHandle> makeEngineHandle(const Scene& scene);
std::unique_ptr<EngineHandle> makeDmdHandle(const Scene& scene);
std::unique_ptr<EngineHandle> makeSmdHandle(const Scene& scene);

} // namespace terrace::cli
