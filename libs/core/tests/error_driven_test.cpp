// Error-driven parameters (core/error_driven.h): the search never loses a caster, never does
// worse than the defaults on its samples, finds the better warp where the seeds say one
// exists, and `auto` is deterministic and holds its choice across frames.
#include "ground_receivers.h"
#include "setup_configs.h"

#include "shadowkit/core/bias.h"
#include "shadowkit/core/error_driven.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace shadowkit;
using namespace shadowkit::core;
using core::testing::ConfigGenerator;

namespace {

constexpr int kViewWidth = core::testing::kGroundWidth, kViewHeight = core::testing::kGroundHeight;
using core::testing::groundReceivers;
using core::testing::groundView;

// Receivers the camera could see: points of its frustum with normals facing the light and
// not edge-on to the eye.
std::vector<ReceiverSample> randomReceivers(const ShadowSetupInputs& in, ConfigGenerator& gen, int count) {
    std::vector<ReceiverSample> samples;
    for (int k = 0; k < count; ++k) {
        const Vec3 p = core::testing::pointInFrustum(in.camera, gen);
        Vec3 n = gen.unitVector();
        if (glm::dot(n, in.light.wsTowardsLight()) < 0.0) n = -n;
        samples.push_back({p, n});
    }
    return samples;
}

} // namespace

// Ten thousand random configurations, every family: the chosen parameters still hold every
// point their technique must hold (the containment the techniques' own tests check), and the
// chosen objective is never above the inputs' own on the same samples.
TEST(ErrorDrivenTest, OptimisedParametersLoseNoCasterAndNeverLoseToTheDefaults) {
    ConfigGenerator gen(16);
    int optimised = 0, improved = 0;
    int optimisedOf[3] = {}, improvedOf[3] = {}; // per family, in `families` order
    for (int i = 0; i < 10000; ++i) {
        ShadowSetupInputs in = gen.next();
        const Technique families[] = {Technique::Lispsm, Technique::Tsm, Technique::Csm};
        in.technique = families[i % 3];
        in.cascades.stabilize = false;
        in.camera.aspect = double(kViewWidth) / kViewHeight;
        if (!validate(in)) continue;
        auto model = SamplingErrorModel::create(in.camera, kViewWidth, kViewHeight, randomReceivers(in, gen, 24));
        ASSERT_TRUE(model);
        auto choice = optimiseParameters(in, *model);
        ASSERT_TRUE(choice) << choice.error();
        auto defaults = computeShadowSetup(in);
        ASSERT_TRUE(defaults);
        const double defaultObjective = samplingObjective(model->figures(*defaults));
        ASSERT_LE(choice->objective, defaultObjective) << "config " << i;
        improved += choice->objective < defaultObjective;
        improvedOf[i % 3] += choice->objective < defaultObjective;
        auto setup = computeShadowSetup(choice->inputs);
        ASSERT_TRUE(setup) << setup.error();
        EXPECT_EQ(samplingObjective(model->figures(*setup)), choice->objective) << "config " << i;
        for (const ShadowView& view : setup->views)
            for (const Vec3& p : core::testing::pointsToHold(choice->inputs, *setup, view)) {
                ASSERT_GT((view.clipFromWorld * Vec4(p, 1.0)).w, 0.0) << describe(*choice) << ", config " << i;
                ASSERT_LE(core::testing::outsideClipCube(view.clipFromWorld, p), 1e-6)
                    << describe(*choice) << ", config " << i;
            }
        ++optimised, ++optimisedOf[i % 3];
    }
    EXPECT_GT(optimised, 9000);
    // The search does find better parameters, often: 3,273 of 10,000 (LiSPSM 1,670 of 3,334,
    // cascades 1,162, TSM 441 — 598 before TSM's warp stopped outgrowing a compact footprint's
    // pixels, which left its search less to find).
    EXPECT_GT(improved, optimised / 4);
    for (int f = 0; f < 3; ++f) EXPECT_GT(improvedOf[f], optimisedOf[f] / 10) << "family " << f; // each family's search
}

// A view low over a ground plane lit from the side (LiSPSM's case, Wimmer et al. 2004 §4.3):
// the search lowers the p95 below both the default n and the uniform limit, and below
// TSM's 80 % rule, with parameters inside the searched ranges.
TEST(ErrorDrivenTest, FindsABetterWarpThanTheDefaultsOnAGroundView) {
    ShadowSetupInputs in = groundView(30.0, 90.0);
    auto model = SamplingErrorModel::create(in.camera, kViewWidth, kViewHeight, groundReceivers(in.camera, 300.0, 60));
    ASSERT_TRUE(model);
    for (const Technique t : {Technique::Lispsm, Technique::Tsm}) {
        in.technique = t;
        const SamplingFigures defaults = model->figures(*computeShadowSetup(in));
        auto choice = optimiseParameters(in, *model);
        ASSERT_TRUE(choice);
        EXPECT_LT(choice->predicted.p95, defaults.p95 * 0.99) << describe(*choice);
        EXPECT_GE(choice->inputs.lispsm.weight, 1.0 / 16.0);
        EXPECT_LE(choice->inputs.lispsm.weight, 16.0);
        EXPECT_GT(choice->setupsTried, 10);
    }
    in.technique = Technique::Focused;
    const double uniform = model->figures(*computeShadowSetup(in)).p95;
    in.technique = Technique::Lispsm;
    EXPECT_LT(optimiseParameters(in, *model)->predicted.p95, uniform / 2.0); // the warp's whole point
}

TEST(ErrorDrivenTest, AutoRanksEveryCandidateOfTheBudgetAndIsDeterministic) {
    const ShadowSetupInputs in = groundView(40.0, 60.0);
    auto model = SamplingErrorModel::create(in.camera, kViewWidth, kViewHeight, groundReceivers(in.camera, 300.0, 40));
    ASSERT_TRUE(model);
    AutoOptions options;
    options.texelBudget = int64_t(4) << 20; // 4 M: 1 x 2048² or 4 x 1024²
    auto ranked = rankCandidates(in, options, *model);
    ASSERT_TRUE(ranked);
    ASSERT_EQ(ranked->size(), 4u + 3u * 2u); // four single maps; 2, 3, 4 cascades, each unwarped and warped
    // Best first; only a near-tie may put a family with a normal offset ahead (next test).
    for (size_t i = 2; i < ranked->size(); ++i) EXPECT_LE((*ranked)[i - 1].objective, (*ranked)[i].objective);
    EXPECT_LE(ranked->front().objective, (1.0 + options.hysteresis) * (*ranked)[1].objective);
    for (const ParameterChoice& c : *ranked) {
        const int maps = c.inputs.technique == Technique::Csm ? c.inputs.cascades.count : 1;
        EXPECT_LE(int64_t(maps) * c.inputs.mapSize * c.inputs.mapSize, options.texelBudget) << describe(c);
        EXPECT_EQ(c.inputs.mapSize, maps == 1 ? 2048 : maps == 4 ? 1024 : c.inputs.mapSize);
    }
    auto first = chooseAuto(in, options, *model), second = chooseAuto(in, options, *model);
    ASSERT_TRUE(first && second);
    EXPECT_EQ(describe(*first), describe(*second));
    EXPECT_EQ(first->objective, second->objective);
    EXPECT_EQ(first->objective, ranked->front().objective);

    options.cascades = 1; // single maps only
    auto single = chooseAuto(in, options, *model);
    ASSERT_TRUE(single);
    EXPECT_NE(single->inputs.technique, Technique::Csm);
    options.cascades = 3;
    auto three = rankCandidates(in, options, *model);
    ASSERT_TRUE(three);
    ASSERT_EQ(three->size(), 2u);
    for (const ParameterChoice& c : *three) EXPECT_EQ(c.inputs.cascades.count, 3);
}

// The model sees sampling, not depth: where focused or psm (no normal offset in their
// recommended bias) are best by less than the hysteresis margin, the best family with a normal
// offset goes first (on a public engine model under a low sun, focused was predicted 0.6 %
// better than LiSPSM and measured 11.50 % wrong against 0.07 %); where they are clearly best
// they stay.
TEST(ErrorDrivenTest, NearTiesGoToAFamilyWithANormalOffset) {
    ConfigGenerator gen(52);
    AutoOptions options;
    options.cascades = 1;
    auto offsets = [](const ParameterChoice& c) {
        return recommendedBias(c.inputs.technique, depthLayoutFor(c.inputs)).normalOffset > 0.0;
    };
    int moved = 0, keptClearBest = 0;
    for (int i = 0; i < 400; ++i) {
        ShadowSetupInputs in = gen.next();
        in.camera.aspect = double(kViewWidth) / kViewHeight;
        if (!validate(in)) continue;
        auto model = SamplingErrorModel::create(in.camera, kViewWidth, kViewHeight, randomReceivers(in, gen, 24));
        ASSERT_TRUE(model);
        auto ranked = rankCandidates(in, options, *model);
        ASSERT_TRUE(ranked);
        double lowest = std::numeric_limits<double>::infinity(), lowestWithOffset = lowest;
        for (const ParameterChoice& c : *ranked) {
            lowest = std::min(lowest, c.objective);
            if (offsets(c)) lowestWithOffset = std::min(lowestWithOffset, c.objective);
        }
        const ParameterChoice& front = ranked->front();
        if (lowestWithOffset <= (1.0 + options.hysteresis) * lowest) {
            EXPECT_TRUE(offsets(front)) << "config " << i << ": " << describe(front);
            EXPECT_EQ(front.objective, lowestWithOffset) << "config " << i;
            moved += front.objective > lowest;
        } else {
            EXPECT_EQ(front.objective, lowest) << "config " << i;
            keptClearBest += !offsets(front);
        }
    }
    EXPECT_GT(moved, 0);         // near-ties happened and were resolved
    EXPECT_GT(keptClearBest, 0); // and a clearly better focused or psm map was still chosen
}

// Hysteresis: a previous choice nearly as good as the best is kept (the camera moved a
// little); one much worse is replaced; with none the best is taken.
TEST(ErrorDrivenTest, AutoKeepsThePreviousChoiceUnlessClearlyBeaten) {
    ShadowSetupInputs in = groundView(35.0, 80.0);
    auto model = SamplingErrorModel::create(in.camera, kViewWidth, kViewHeight, groundReceivers(in.camera, 300.0, 40));
    ASSERT_TRUE(model);
    AutoOptions options;
    options.cascades = 1;
    auto ranked = rankCandidates(in, options, *model);
    ASSERT_TRUE(ranked);
    ASSERT_GE(ranked->size(), 2u);
    const ParameterChoice& best = ranked->front();
    // The runner-up within the band is kept, one outside it is not.
    for (const ParameterChoice& other : *ranked) {
        if (other.objective == best.objective) continue;
        options.hysteresis = 0.999 * (1.0 - best.objective / other.objective); // just short of other's distance
        auto replaced = chooseAuto(in, options, *model, &other);
        ASSERT_TRUE(replaced);
        EXPECT_EQ(replaced->objective, best.objective) << describe(other);
        options.hysteresis = std::min(0.999, 1.001 * (1.0 - best.objective / other.objective));
        auto kept = chooseAuto(in, options, *model, &other);
        ASSERT_TRUE(kept);
        EXPECT_EQ(describe(*kept), describe(other));
        break;
    }
}

TEST(ErrorDrivenTest, BadOptionsAreErrorsNamingTheField) {
    AutoOptions options;
    options.texelBudget = 100;
    auto s = validate(options);
    ASSERT_FALSE(s);
    EXPECT_EQ(s.errorInfo().field, "auto.texel_budget");
    options = AutoOptions{};
    options.cascades = 9;
    EXPECT_EQ(validate(options).errorInfo().field, "auto.cascades");
    options = AutoOptions{};
    options.cascades = 8;
    options.texelBudget = 8 * 15 * 15; // eight maps of 15² are below the smallest map
    EXPECT_EQ(validate(options).errorInfo().field, "auto.texel_budget");
    options = AutoOptions{};
    options.hysteresis = 1.0;
    EXPECT_EQ(validate(options).errorInfo().field, "auto.hysteresis");
    options = AutoOptions{};
    options.searchSamples = 19; // the p95 of 19 samples is their largest
    EXPECT_EQ(validate(options).errorInfo().field, "auto.search_samples");
    // No samples: nothing to judge by, so the default technique as it is, not an error.
    const ShadowSetupInputs in = groundView(40.0, 60.0);
    auto empty = SamplingErrorModel::create(in.camera, kViewWidth, kViewHeight, {});
    ASSERT_TRUE(empty);
    auto choice = chooseAuto(in, AutoOptions{}, *empty);
    ASSERT_TRUE(choice);
    EXPECT_EQ(choice->inputs.technique, defaultTechnique());
    EXPECT_EQ(choice->inputs.tsm.focusFraction, in.tsm.focusFraction);
    EXPECT_EQ(choice->inputs.mapSize, 2048);
}
