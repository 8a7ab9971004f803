// A shadow set-up is per-frame work: for the usual cases (a single map, or up to eight
// cascades from λ) it must not touch the heap. This test binary replaces the global
// operator new to count allocations inside the measured calls only.
#include "shadowkit/core/shadow_setup.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <new>

namespace {
bool g_counting = false;
int g_allocations = 0;
} // namespace

void* operator new(size_t bytes) {
    if (g_counting) ++g_allocations;
    if (void* p = std::malloc(bytes > 0 ? bytes : 1)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, size_t) noexcept { std::free(p); }

using namespace shadowkit::core;

TEST(AllocationTest, ComputingASetupAllocatesNothingForEveryTechniqueAndView) {
    const Aabb scene = Aabb::fromMinMax(Vec3(-512, -5, -512), Vec3(512, 60, 512));
    PerspectiveCamera level;
    level.wsEye = Vec3(3, 2, 7);
    level.wsDirection = Vec3(0.2, 0, -1);
    PerspectiveCamera aerial = level;
    aerial.wsEye = Vec3(0, 80, 200);
    aerial.wsDirection = Vec3(0, -0.7, -1);
    aerial.zFar = 1500;
    for (const PerspectiveCamera& camera : {level, aerial})
        for (const double elevation : {30.0, 85.0})
            for (const TechniqueInfo& t : allTechniques()) {
                ShadowSetupInputs in{.camera = camera,
                                     .light = DirectionalLight::fromSunAngles(elevation, 120).value(),
                                     .wsSceneBounds = scene,
                                     .technique = t.technique};
                in.cascades.count = 8;
                g_allocations = 0;
                g_counting = true;
                const bool ok = static_cast<bool>(computeShadowSetup(in));
                g_counting = false;
                EXPECT_TRUE(ok) << t.name;
                EXPECT_EQ(g_allocations, 0) << t.name << ", sun at " << elevation << "°";
            }
}

TEST(AllocationTest, TheCounterSeesAllocations) {
    // The control: the replacement operator new is the one in use.
    g_allocations = 0;
    g_counting = true;
    auto* p = new std::vector<int>(100);
    g_counting = false;
    delete p;
    EXPECT_GE(g_allocations, 2);
}
