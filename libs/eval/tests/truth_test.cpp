// The ray-traced truth against shadows known analytically.
#include "truth_scenes.h"

#include "shadowkit/eval/soft_truth.h"
#include "shadowkit/eval/truth.h"
#include "shadowkit/scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>

using namespace shadowkit;
using namespace shadowkit::test;

namespace {

// Runs the truth and, for every ground pixel facing the light, compares with
// `analyticShadow(p)` (nullopt: too close to the analytic boundary to call).
template <class Analytic>
void expectTruthMatches(const scene::Scene& s, const core::DirectionalLight& sun, Analytic analyticShadow) {
    auto rays = eval::RayScene::build(s);
    ASSERT_TRUE(rays) << rays.error();
    const core::PerspectiveCamera cam = cameraLookingAtOrigin();
    const eval::TruthBuffers truth = eval::computeTruth(**rays, cam, sun, 160, 120);
    int compared = 0, shadowed = 0, mismatches = 0;
    for (size_t i = 0; i < truth.surfaceId.size(); ++i) {
        if (truth.surfaceId[i] != kGroundId || !truth.facesLight[i]) continue;
        const std::optional<bool> expected = analyticShadow(truth.wsPosition[i]);
        if (!expected) continue;
        ++compared;
        shadowed += *expected;
        mismatches += (truth.lit[i] == 0) != *expected;
    }
    EXPECT_GT(compared, 10000);
    EXPECT_GT(shadowed, 100); // the shadow is actually in view
    EXPECT_EQ(mismatches, 0);
}

} // namespace

TEST(TruthTest, BoxOverPlaneUnderAnObliqueSunMatchesTheAnalyticShadow) {
    scene::Mesh box;
    scene::addBox(box, glm::mat4(1.0f), {1, 0.5f, 1.5f}, glm::vec3(0.8f));
    const glm::vec3 centre(0, 2.5f, 0);
    const scene::Scene s = groundAnd(box, glm::translate(glm::mat4(1.0f), centre));
    const core::DirectionalLight sun = core::DirectionalLight::fromSunAngles(50, 120).value();
    const core::Vec3 lo = core::Vec3(centre) - core::Vec3(1, 0.5, 1.5),
                     hi = core::Vec3(centre) + core::Vec3(1, 0.5, 1.5);
    // Slab test of the ray p + t·towardsLight against the box, with a margin band where
    // pixel-centre rounding could go either way.
    expectTruthMatches(s, sun, [&](const core::Vec3& p) -> std::optional<bool> {
        const core::Vec3 d = sun.wsTowardsLight();
        auto hits = [&](double grow) {
            double t0 = 0.0, t1 = 1e9;
            for (int a = 0; a < 3; ++a) {
                const double ta = (lo[a] - grow - p[a]) / d[a], tb = (hi[a] + grow - p[a]) / d[a];
                t0 = std::max(t0, std::min(ta, tb));
                t1 = std::min(t1, std::max(ta, tb));
            }
            return t0 <= t1;
        };
        if (hits(-1e-3) != hits(1e-3)) return std::nullopt;
        return hits(0.0);
    });
}

TEST(TruthTest, SphereOverPlaneUnderAnObliqueSunMatchesTheAnalyticShadow) {
    scene::Mesh sphere;
    const float radius = 1.2f;
    scene::addIcosphere(sphere, glm::mat4(1.0f), 4, radius, glm::vec3(0.8f));
    const core::Vec3 centre(0.5, 3.0, -0.5);
    const scene::Scene s = groundAnd(sphere, glm::translate(glm::mat4(1.0f), glm::vec3(centre)));
    const core::DirectionalLight sun = core::DirectionalLight::fromSunAngles(35, 200).value();
    // The tessellated sphere lies between its inscribed (≈0.998 r at 4 subdivisions) and
    // circumscribed radius: only points whose light ray passes outside that band are called.
    expectTruthMatches(s, sun, [&](const core::Vec3& p) -> std::optional<bool> {
        const core::Vec3 d = sun.wsTowardsLight();
        const core::Vec3 toCentre = centre - p;
        const double along = glm::dot(toCentre, d);
        if (along <= 0.0) return false;
        const double miss = glm::length(toCentre - along * d); // closest approach of the ray
        if (miss > radius * 1.001) return false;
        if (miss < radius * 0.99) return true;
        return std::nullopt;
    });
}

TEST(TruthTest, PrimaryRaysPutTheirParameterOnTheViewAxis) {
    const core::PerspectiveCamera cam = cameraLookingAtOrigin();
    const core::Vec3 forward = glm::normalize(cam.wsDirection);
    for (auto [x, y] : {std::pair{0, 0}, std::pair{159, 119}, std::pair{80, 60}})
        EXPECT_NEAR(glm::dot(eval::primaryRayDirection(cam, 160, 120, x, y), forward), 1.0, 1e-12);
}

// Local lights: the finite shadow ray to a point light, its range, and a spot light's cone,
// against the analytic answer for a box over the ground.
TEST(TruthTest, PointAndSpotLightsMatchTheAnalyticShadowRangeAndCone) {
    scene::Mesh box;
    scene::addBox(box, glm::mat4(1.0f), {1, 0.5f, 1.5f}, glm::vec3(0.8f));
    const core::Vec3 centre(0, 2.5, 0), half(1, 0.5, 1.5);
    const scene::Scene s = groundAnd(box, glm::translate(glm::mat4(1.0f), glm::vec3(centre)));
    auto rays = eval::RayScene::build(s);
    ASSERT_TRUE(rays) << rays.error();
    const eval::TruthBuffers hits = eval::computeTruth(
        **rays, cameraLookingAtOrigin(), core::DirectionalLight::fromSunAngles(50, 120).value(), 160, 120);
    // Does the segment p → light cross the box (grown by `grow`)?
    auto blocked = [&](const core::Vec3& p, const core::Vec3& light, double grow) {
        const core::Vec3 d = light - p;
        double t0 = 0.0, t1 = 1.0;
        for (int a = 0; a < 3; ++a) {
            const double ta = (centre[a] - half[a] - grow - p[a]) / d[a],
                         tb = (centre[a] + half[a] + grow - p[a]) / d[a];
            t0 = std::max(t0, std::min(ta, tb));
            t1 = std::min(t1, std::max(ta, tb));
        }
        return t0 <= t1;
    };
    const core::PointLight lamp{.wsPosition = {0.5, 6.0, 0.3}, .range = 12.0};
    const core::SpotLight torch{
        .wsPosition = {-6.0, 6.0, 0.0}, .wsDirection = {1.0, -0.8, 0.0}, .coneDegrees = 50.0, .range = 20.0};
    const std::vector<uint8_t> byLamp = eval::litAt(**rays, hits, lamp), byTorch = eval::litAt(**rays, hits, torch);
    int compared = 0, shadowed = 0, outOfRange = 0, outsideCone = 0, mismatches = 0;
    for (size_t i = 0; i < hits.surfaceId.size(); ++i) {
        if (hits.surfaceId[i] != kGroundId) continue;
        const core::Vec3 p = hits.wsPosition[i];
        // The lamp: unlit beyond its range, else lit unless the box is in the way.
        const double d = glm::distance(p, lamp.wsPosition);
        if (d > lamp.range + 1e-3) {
            ++outOfRange;
            mismatches += byLamp[i] != 0;
        } else if (d < lamp.range - 1e-3 && blocked(p, lamp.wsPosition, -1e-3) == blocked(p, lamp.wsPosition, 1e-3)) {
            ++compared;
            shadowed += blocked(p, lamp.wsPosition, 0.0);
            mismatches += (byLamp[i] == 0) != blocked(p, lamp.wsPosition, 0.0);
        }
        // The torch: nothing outside its cone is lit by it.
        const core::Vec3 toP = glm::normalize(p - torch.wsPosition);
        const double cosAngle = glm::dot(toP, glm::normalize(torch.wsDirection)),
                     cosHalf = std::cos(glm::radians(25.0));
        if (cosAngle < cosHalf - 1e-4) {
            ++outsideCone;
            mismatches += byTorch[i] != 0;
        } else if (cosAngle > cosHalf + 1e-4 &&
                   blocked(p, torch.wsPosition, -1e-3) == blocked(p, torch.wsPosition, 1e-3)) {
            mismatches += (byTorch[i] == 0) != blocked(p, torch.wsPosition, 0.0);
        }
    }
    EXPECT_GT(compared, 5000);
    EXPECT_GT(shadowed, 100);    // the box's shadow is in view
    EXPECT_GT(outOfRange, 100);  // so is ground beyond the lamp's range
    EXPECT_GT(outsideCone, 100); // and ground outside the torch's cone
    EXPECT_EQ(mismatches, 0);
}

TEST(TruthTest, AFaceAlongTheSunsRaysIsNotScoredWhicheverWayRoundingTurnsIt) {
    // A box's +z face seen by the camera, under a sun travelling across it (-x, down) tilted
    // `tilt` towards +z: at ±1e-7 — the N·L a rotated model matrix leaves on a face parallel to
    // the rays — the face gets 1e-7 of the sun's light lit or shadowed, and is neither
    // scored nor sampled (hard or soft truth); tilted 0.01 it faces the sun, unblocked.
    scene::Mesh box;
    scene::addBox(box, glm::mat4(1.0f), {1, 0.5f, 1.5f}, glm::vec3(0.8f));
    const scene::Scene s = groundAnd(box, glm::translate(glm::mat4(1.0f), {0, 2.5f, 0}));
    auto rays = eval::RayScene::build(s);
    ASSERT_TRUE(rays) << rays.error();
    constexpr uint32_t kBoxId = kGroundId + 1;
    for (const double tilt : {1e-7, -1e-7, 1e-2}) {
        const core::DirectionalLight sun = core::DirectionalLight::fromDirection({-1.0, -0.6, -tilt}).value();
        const eval::TruthBuffers truth = eval::computeTruth(**rays, cameraLookingAtOrigin(), sun, 160, 120);
        const eval::SoftTruth soft = eval::computeSoftTruth(
            **rays, truth, {.wsTowardsSun = sun.wsTowardsLight(), .angularDiameterDegrees = 0.53}, {.samples = 16});
        int side = 0, sideFacing = 0, sideLit = 0, sideSampled = 0, top = 0, topFacing = 0;
        for (size_t i = 0; i < truth.surfaceId.size(); ++i) {
            if (truth.surfaceId[i] != kBoxId) continue;
            const glm::vec3 n = truth.wsNormal[i];
            const bool isSide = n.z > 0.999f, isTop = n.y > 0.999f;
            side += isSide;
            sideFacing += isSide && truth.facesLight[i];
            sideLit += isSide && truth.lit[i];
            sideSampled += isSide && !std::isnan(soft.visibility[i]);
            top += isTop;
            topFacing += isTop && truth.facesLight[i];
        }
        SCOPED_TRACE("tilt " + std::to_string(tilt));
        EXPECT_GT(side, 100);
        EXPECT_GT(top, 100);
        EXPECT_EQ(topFacing, top); // the top faces the sun whatever the tilt
        const int expected = tilt > 1e-3 ? side : 0;
        EXPECT_EQ(sideFacing, expected);
        EXPECT_EQ(sideLit, expected);
        EXPECT_EQ(sideSampled, expected);
    }
}

TEST(TruthTest, PacketsOfRaysAnswerExactlyWhatOneRayAtATimeDoes) {
    // The truth traces 8-wide packets; the golden figures were recorded one ray at a time. Rays
    // from a camera over a sphere, a box and the ground — coherent tiles, scattered rays, a
    // partial last packet, finite and infinite ranges, origins 1,000 km out — must hit the same
    // instances at the same parameters with the same normals, and be blocked alike.
    for (const double offset : {0.0, 1.0e6}) {
        scene::Mesh sphere;
        scene::addIcosphere(sphere, glm::mat4(1.0f), 3, 1.5f, glm::vec3(0.8f));
        scene::Scene s = groundAnd(sphere, glm::translate(glm::mat4(1.0f), {0, 2.5f, 0}));
        s.wsOrigin = core::Vec3(offset, 0.0, offset);
        auto rays = eval::RayScene::build(s);
        ASSERT_TRUE(rays) << rays.error();
        core::PerspectiveCamera cam = cameraLookingAtOrigin();
        cam.wsEye += s.wsOrigin;
        std::vector<eval::Ray> batch;
        for (int y = 0; y < 40; ++y)
            for (int x = 0; x < 53; ++x) // 2,121 rays with the one below: a last packet of one ray
                batch.push_back({cam.wsEye, eval::primaryRayDirection(cam, 53, 40, (x * 7) % 53, y), cam.zNear,
                                 y % 3 == 0 ? 18.0 : cam.zFar});
        batch.push_back({cam.wsEye, eval::primaryRayDirection(cam, 53, 40, 26, 20), cam.zNear, cam.zFar});
        std::vector<uint8_t> hit(batch.size());
        std::vector<eval::RayHit> hits(batch.size());
        (*rays)->intersect(batch, hit, hits);
        std::vector<eval::Ray> shadowRays;
        int hitCount = 0;
        for (size_t i = 0; i < batch.size(); ++i) {
            eval::RayHit one;
            const bool h = (*rays)->intersect(batch[i].origin, batch[i].direction, batch[i].tNear, batch[i].tFar, one);
            ASSERT_EQ(bool(hit[i]), h) << "ray " << i;
            if (!h) continue;
            ++hitCount;
            EXPECT_EQ(hits[i].t, one.t);
            EXPECT_EQ(hits[i].instance, one.instance);
            EXPECT_EQ(hits[i].wsGeometricNormal, one.wsGeometricNormal);
            const core::Vec3 p = batch[i].origin + one.t * batch[i].direction;
            shadowRays.push_back({p + 0.01 * one.wsGeometricNormal, glm::normalize(core::Vec3(0.4, 1.0, 0.3)), 0.0,
                                  i % 2 ? 3.0 : std::numeric_limits<double>::infinity()});
        }
        EXPECT_GT(hitCount, 1500);
        std::vector<uint8_t> blocked(shadowRays.size());
        (*rays)->occluded(shadowRays, blocked);
        int shadowed = 0;
        for (size_t i = 0; i < shadowRays.size(); ++i) {
            const eval::Ray& r = shadowRays[i];
            ASSERT_EQ(bool(blocked[i]), (*rays)->occluded(r.origin, r.direction, r.tNear, r.tFar)) << "ray " << i;
            shadowed += blocked[i];
        }
        EXPECT_GT(shadowed, 20); // the sphere shadows some of them
    }
}

TEST(TruthTest, CameraRaysPassTheBackOfASingleSidedSurfaceWhileLightMeetsBothSides) {
    // A 6 m card 2 m over the ground facing down, seen from above: its back. The camera pass
    // culls it there unless its material is double-sided or its batch mirrored (gl::GpuScene);
    // the truth's camera rays must show what the raster shows, and its light must still be
    // stopped by the card, whichever side faces the sun.
    scene::Mesh card;
    const glm::mat4 partFacingDown =
        glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), {1, 0, 0}) * glm::scale(glm::mat4(1.0f), {6, 6, 1});
    scene::addCard(card, partFacingDown, {0, 0}, {1, 1}, glm::vec3(0.8f));
    const glm::mat4 worldFromCard = glm::translate(glm::mat4(1.0f), {-1.5f, 2.0f, -4.0f});
    const core::DirectionalLight sun = core::DirectionalLight::fromSunAngles(70, 120).value();
    const core::PerspectiveCamera cam = cameraLookingAtOrigin();
    constexpr uint32_t kCardId = 2;
    struct Seen {
        int card = 0, shadedGround = 0;
    };
    auto seen = [&](const scene::Scene& s) {
        auto rays = eval::RayScene::build(s);
        EXPECT_TRUE(rays) << rays.error();
        const eval::TruthBuffers truth = eval::computeTruth(**rays, cam, sun, 160, 120);
        Seen counts;
        for (size_t i = 0; i < truth.surfaceId.size(); ++i) {
            counts.card += truth.surfaceId[i] == kCardId;
            counts.shadedGround += truth.surfaceId[i] == kGroundId && truth.facesLight[i] && !truth.lit[i];
        }
        return counts;
    };

    scene::Scene singleSided = groundAnd(card, worldFromCard);
    const Seen fromBehind = seen(singleSided);
    EXPECT_EQ(fromBehind.card, 0);
    EXPECT_GT(fromBehind.shadedGround, 500); // its shadow, seen through it (879 of 19,200 pixels)

    scene::Scene doubleSided = singleSided;
    doubleSided.materials.push_back({});
    doubleSided.materials.back().doubleSided = true;
    doubleSided.meshes[1].material = 0;
    const Seen both = seen(doubleSided);
    EXPECT_GT(both.card, 500);
    EXPECT_LT(both.shadedGround, fromBehind.shadedGround); // the card hides part of its shadow

    // Mirrored through x = -1.5 (its own centre line): the same card, wound the other way; its
    // batch is drawn from both sides.
    scene::Scene mirrored = singleSided;
    mirrored.batches[1].worldFromObject[0] = worldFromCard * glm::scale(glm::mat4(1.0f), {-1, 1, 1});
    EXPECT_TRUE(mirrored.batches[1].mirrored());
    EXPECT_EQ(seen(mirrored).card, both.card);

    // Turned to face up, single-sided: its front, seen.
    scene::Scene facingUp = singleSided;
    facingUp.batches[1].worldFromObject[0] =
        worldFromCard * glm::rotate(glm::mat4(1.0f), glm::radians(180.0f), {0, 0, 1});
    EXPECT_EQ(seen(facingUp).card, both.card);

    // One ray at a time answers as the packets do: through the card's middle, its back or the ground.
    auto rays = eval::RayScene::build(singleSided);
    ASSERT_TRUE(rays) << rays.error();
    const core::Vec3 through = glm::normalize(core::Vec3(-1.5, 2.0, -1.0) - cam.wsEye);
    eval::RayHit hit;
    ASSERT_TRUE((*rays)->intersect(cam.wsEye, through, 0.0, 100.0, hit));
    EXPECT_EQ(hit.instance + 1, kCardId);
    ASSERT_TRUE((*rays)->intersect(cam.wsEye, through, 0.0, 100.0, hit, eval::Faces::AsTheCameraSees));
    EXPECT_EQ(hit.instance + 1, kGroundId);
}
