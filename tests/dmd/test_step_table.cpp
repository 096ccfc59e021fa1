// Step tables with a hard core (core/step_table.hpp) and their DMD (core/step_potential.hpp):
// the tables, their validation and generators; the scene keys; and the engine on them — energy
// conserved to round-off, every event at the radius it belongs to (a brute-force check of each
// pair's distance against its terrace), the core never entered, a lattice with pairs on a step
// started without a stall.
#include "core/initial_state.hpp"
#include "core/sphere.hpp"
#include "core/step_potential.hpp"
#include "core/step_table.hpp"
#include "dmd/scene_engine.hpp"
#include "dmd/testing.hpp"
#include <cmath>
#include <cstdlib>
#include <gtest/gtest.h>
#include <limits>
#include <string>

using terrace::dmd::testing::Probe;
using namespace terrace;

namespace {

using StepEngine = dmd::SceneEngine<Sphere, StepPotential>;

/// The message of the SceneError `f` throws ("" when none).
template <class F> std::string errorOf(F&& f) {
    try {
        f();
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

nlohmann::json stepScene(nlohmann::json potential, int n, double density, double temperature) {
    potential["kind"] = "steps";
    potential["epsilon"] = 1.0;
    potential["sigma"] = 1.0;
    return {{"body", {{"kind", "sphere"}, {"mass", 1.0}}},
            {"potential", potential},
            {"state", {{"n", n}, {"density", density}, {"temperature", temperature}}}};
}

/// Every listed pair's terrace against the one its distance puts it on (all pairs, O(N²)): the
/// brute-force check that no crossing went unseen. Pairs within `onStep` (σ) of a radius are
/// skipped: an event there is due now. Returns the number of pairs checked off terrace 0.
int checkAllPairs(const StepEngine& e, const StepPotential& p, double onStep = 1e-9) {
    const System<Sphere, StepPotential> s = e.system();
    const auto& table = p.table;
    int bound = 0;
    for (int i = 0; i < s.size(); ++i)
        for (int j = i + 1; j < s.size(); ++j) {
            const double r = s.box.minimumImage(s.bodies[i].r - s.bodies[j].r).norm() / p.sigma;
            EXPECT_GE(r, table.hardCore * (1.0 - 1e-12)) << "pair " << i << ", " << j;
            bool near = std::abs(r - table.hardCore) < onStep;
            int expected = 0;
            for (std::size_t k = 0; k < table.radii.size(); ++k) {
                near = near || std::abs(r - table.radii[k]) < onStep;
                if (r < table.radii[k]) expected = int(k) + 1;
            }
            if (near) continue;
            EXPECT_EQ(Probe::terrace(e, i, j), expected)
                << "pair " << i << ", " << j << " at r = " << r;
            bound += expected != 0;
        }
    return bound;
}

} // namespace

TEST(StepEngine, SquareWellConservesEnergyAndMissesNoEvent) {
    const Scene s = sceneFromJson(
        stepScene({{"steps", "square_well"}, {"lambda", 1.5}}, 216, 0.5, 1.5), "<sw>");
    const StepPotential p = stepPotential(s);
    StepEngine e(buildInitialState<Sphere, StepPotential>(s, p), s);
    if (std::getenv("NOHOLD")) Probe::setHoldScreen(e, false);
    const double e0 = e.kineticEnergy() + e.potentialEnergy();
    for (int block = 0; block < 10; ++block) {
        e.advanceTo(e.time() + 0.5);
        EXPECT_NEAR(e.kineticEnergy() + e.potentialEnergy(), e0, 1e-11 * std::abs(e0));
    }
    EXPECT_GT(checkAllPairs(e, p), 0);
}
