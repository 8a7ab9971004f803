// The virtual page cache's policy without a GL context: a budget caps each frame's pages and
// serves the coarsest levels first, a new sun's pages replace the old ones only a whole level at
// a time, a mover invalidates exactly the pages under its old and new boxes, a tiny pool falls
// back and says so, a cached page is never drawn again while nothing changed, requests read
// frames late ask for the pages their own frame marked, or for nothing once the sun has moved,
// and the toroidal page table keeps a page's entry while its window moves, listing as changed
// exactly the entries that differ.
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/core/virtual_clipmap.h"
#include "shadowkit/core/virtual_page_cache.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <tuple>
#include <vector>

using namespace shadowkit::core;

namespace {

// A small clipmap (windows of 32² pages of 32 texels) over a 200 m box, eye 1.8 m up.
ShadowSetup virtualSetup(const Vec3& wsTowardsSun = Vec3(0.5, 1.0, 0.3), const Vec3& wsEye = Vec3(0.0, 1.8, 0.0)) {
    ShadowSetupInputs in;
    in.technique = Technique::Virtual;
    in.camera.wsEye = wsEye;
    in.camera.wsDirection = Vec3(0.0, -0.3, -1.0);
    in.camera.zNear = 0.5;
    in.camera.zFar = 200.0;
    in.light = DirectionalLight{-glm::normalize(wsTowardsSun)};
    in.wsSceneBounds = Aabb::fromMinMax(Vec3(-100.0, -2.0, -100.0), Vec3(100.0, 20.0, 100.0));
    in.virtualMaps.virtualTexels = 1024;
    in.virtualMaps.pageTexels = 32;
    in.virtualMaps.imageHeight = 180;
    in.visibleDepth = Vec2(3.0, 60.0);
    return computeShadowSetup(in).value();
}

// Receivers on the ground in front of the eye.
std::vector<Vec3> receivers() {
    std::vector<Vec3> points;
    for (double x = -12.0; x <= 12.0; x += 1.5)
        for (double z = -40.0; z <= -3.0; z += 1.5) points.emplace_back(x, 0.0, z);
    return points;
}

constexpr int kGuard = 2;

using Key = std::tuple<int, int64_t, int64_t>; // exponent, x, y
Key keyOf(const PageKey& k) { return {k.exponent, k.x, k.y}; }

// What the marking pass (virtual_mark.comp) would read back: for every receiver, its page in
// every level's window — the level rule's page and all its coarser fallbacks —, found through
// the window's own clip matrix (a window kept from an older sun projects in that sun's light).
std::vector<uint32_t> requestBits(const ShadowSetup& setup, std::span<const ShadowView> windows,
                                  std::set<Key>* keys = nullptr) {
    const int pages = setup.clipmap->pagesPerSide();
    const size_t perLevel = size_t(pages) * pages;
    std::vector<uint32_t> bits((perLevel * windows.size() + 31) / 32, 0u);
    for (const Vec3& p : receivers())
        for (size_t l = 0; l < windows.size(); ++l) {
            const Vec4 clip = windows[l].clipFromWorld * Vec4(p, 1.0);
            const Vec2 page = glm::floor((Vec2(clip) / clip.w * 0.5 + 0.5) * double(pages));
            if (page.x < 0.0 || page.y < 0.0 || page.x >= pages || page.y >= pages) continue;
            const size_t i = l * perLevel + size_t(page.y) * pages + size_t(page.x);
            bits[i / 32] |= 1u << (i % 32);
            const ClipmapLevel& level = std::get<ClipmapLevel>(windows[l].warp);
            if (keys)
                keys->insert({level.exponent, level.firstPageX + int64_t(page.x), level.firstPageY + int64_t(page.y)});
        }
    return bits;
}

// One frame: marks, requests, "draws" (rendered()); returns the keys drawn.
std::vector<Key> frame(VirtualPageCache& cache, const ShadowSetup& setup, int budget,
                       std::span<const Aabb> moved = {}) {
    const auto& windows = cache.beginFrame(setup, pageContentOf(*setup.clipmap, kGuard), budget, Vec3(0.0, 1.8, 0.0));
    const std::vector<uint32_t> standing = requestBits(setup, windows.standing);
    const std::vector<uint32_t> back = windows.drawingBack ? requestBits(setup, windows.back) : std::vector<uint32_t>{};
    cache.request(standing, back, moved);
    std::vector<Key> drawn;
    for (const auto& p : cache.pagesToRender()) drawn.push_back(keyOf(p.key));
    cache.rendered();
    return drawn;
}

int exponentOf(const Key& k) { return std::get<0>(k); }

// Where page (x, y) of level `l`'s window (counted from its first page) has its entry in the
// table of `shown`: toroidal — its grid index modulo the pages a side — written out here rather
// than through core's pageTableCellOf.
size_t tableIndexOf(const ShadowSetup& shown, size_t l, int64_t x, int64_t y) {
    const int64_t n = shown.clipmap->pagesPerSide();
    const ClipmapLevel& level = std::get<ClipmapLevel>(shown.views[l].warp);
    const auto wrap = [n](int64_t i) { return i % n < 0 ? i % n + n : i % n; };
    return size_t(int64_t(l) * n * n + wrap(level.firstPageY + y) * n + wrap(level.firstPageX + x));
}

} // namespace

TEST(VirtualPageCacheTest, AFrameDrawsEveryRequestedPageOnceThenNothingWhileNothingChanges) {
    const ShadowSetup setup = virtualSetup();
    std::set<Key> requested;
    requestBits(setup, setup.views, &requested);
    ASSERT_GT(requested.size(), 20u);
    VirtualPageCache cache;
    cache.configure(4096, kGuard);
    const std::vector<Key> first = frame(cache, setup, 0);
    EXPECT_EQ(std::set<Key>(first.begin(), first.end()), requested);
    EXPECT_EQ(first.size(), requested.size()); // none twice
    EXPECT_EQ(cache.stats().pagesResident, static_cast<int>(requested.size()));
    EXPECT_TRUE(frame(cache, setup, 0).empty()); // cached
    // Every requested page has its slot in the table, and no slot serves two pages.
    const auto table = cache.pageTable();
    std::set<uint32_t> slots;
    for (const uint32_t entry : table) {
        if (entry == 0) continue;
        EXPECT_TRUE(slots.insert(entry).second);
    }
    EXPECT_EQ(slots.size(), requested.size());
    // Without a budget, a new sun drops every page at once: all drawn again.
    const ShadowSetup other = virtualSetup(Vec3(-0.4, 1.0, 0.2));
    std::set<Key> otherRequested;
    requestBits(other, other.views, &otherRequested);
    EXPECT_EQ(frame(cache, other, 0).size(), otherRequested.size());
    EXPECT_EQ(cache.stats().levelsBehind, 0);
}

TEST(VirtualPageCacheTest, ABudgetCapsEachFrameCoarsestLevelFirstAndConvergesOnTheSamePages) {
    const ShadowSetup setup = virtualSetup();
    std::set<Key> requested;
    requestBits(setup, setup.views, &requested);
    VirtualPageCache cache;
    cache.configure(4096, kGuard);
    constexpr int kBudget = 5;
    std::vector<Key> all;
    int frames = 0;
    for (; frames < 200; ++frames) {
        const std::vector<Key> drawn = frame(cache, setup, kBudget);
        if (drawn.empty()) break;
        EXPECT_LE(drawn.size(), size_t(kBudget));
        // Coarsest first: nothing drawn in a frame is coarser than what an earlier frame drew.
        if (!all.empty()) {
            EXPECT_LE(exponentOf(drawn.front()), exponentOf(all.back())) << "frame " << frames;
        }
        EXPECT_EQ(cache.stats().pagesDeferred + cache.stats().pagesRendered,
                  static_cast<int>(requested.size()) - static_cast<int>(all.size()));
        all.insert(all.end(), drawn.begin(), drawn.end());
    }
    EXPECT_GT(frames, 3) << "the budget held every page: the test checks nothing";
    EXPECT_EQ(std::set<Key>(all.begin(), all.end()), requested);
    EXPECT_EQ(all.size(), requested.size());
}

TEST(VirtualPageCacheTest, TheOldSunsPagesServeUntilALevelIsCompleteForTheNewOne) {
    const ShadowSetup sunA = virtualSetup(), sunB = virtualSetup(Vec3(-0.4, 1.0, 0.2));
    VirtualPageCache cache;
    cache.configure(4096, kGuard);
    constexpr int kBudget = 4;
    for (int f = 0; f < 200 && !frame(cache, sunA, kBudget).empty(); ++f) {
    }
    const int levels = static_cast<int>(sunB.views.size());
    int framesBehind = 0, switches = 0;
    std::vector<bool> onB(size_t(levels), false);
    for (int f = 0; f < 400; ++f) {
        const std::vector<Key> drawn = frame(cache, sunB, kBudget);
        EXPECT_LE(drawn.size(), size_t(kBudget));
        const ShadowSetup& shown = cache.shown();
        ASSERT_EQ(static_cast<int>(shown.views.size()), levels);
        // Each level is shown whole from one sun: every page its receivers request in the window
        // it is shown in has a slot in the table (none half drawn, none of the other sun).
        const std::vector<uint32_t> bits = requestBits(sunB, shown.views);
        const auto table = cache.pageTable();
        const size_t pages = size_t(shown.clipmap->pagesPerSide()), perLevel = pages * pages;
        for (size_t i = 0; i < table.size(); ++i) { // i: the bit of window page i % perLevel, level i / perLevel
            const bool requestedHere = (bits[i / 32] >> (i % 32) & 1u) != 0;
            const size_t entry = tableIndexOf(shown, i / perLevel, int64_t(i % pages), int64_t(i % perLevel / pages));
            EXPECT_TRUE(!requestedHere || table[entry] != 0u) << "frame " << f << " window page " << i;
        }
        for (int l = 0; l < levels; ++l) {
            const bool fromB = shown.views[size_t(l)].clipFromWorld == sunB.views[size_t(l)].clipFromWorld;
            EXPECT_TRUE(fromB || !onB[size_t(l)]) << "level " << l << " went back to the old sun";
            switches += fromB && !onB[size_t(l)];
            onB[size_t(l)] = fromB;
        }
        framesBehind += cache.stats().levelsBehind > 0;
        if (cache.stats().levelsBehind == 0 && drawn.empty()) break;
    }
    EXPECT_EQ(switches, levels);
    EXPECT_GT(framesBehind, 2) << "the new sun's pages fit one frame: the test checks little";
    EXPECT_EQ(cache.stats().levelsBehind, 0);
    EXPECT_EQ(cache.stats().lagFrames, 0);
}

TEST(VirtualPageCacheTest, AMoverInvalidatesExactlyThePagesUnderItsOldAndNewBoxesInEveryLevel) {
    const ShadowSetup setup = virtualSetup();
    VirtualPageCache cache;
    cache.configure(4096, kGuard);
    std::set<Key> requested;
    requestBits(setup, setup.views, &requested);
    frame(cache, setup, 0);
    const Aabb oldBox = Aabb::fromMinMax(Vec3(-1.0, 0.0, -10.0), Vec3(1.0, 2.0, -8.0));
    const Aabb newBox = Aabb::fromMinMax(Vec3(3.0, 0.0, -10.0), Vec3(5.0, 2.0, -8.0));
    const Aabb moved[] = {oldBox, newBox};
    // Expected independently of the light-space rectangles the cache uses: a page is redrawn when
    // either box's corners, through the page's own clip matrix (guard band included), reach its
    // square.
    std::set<Key> expected;
    for (const Key& k : requested) {
        const PageKey key{std::get<0>(k), std::get<1>(k), std::get<2>(k)};
        const Mat4 clipFromWorld = clipmapPageClipFromWorld(*setup.clipmap, key, kGuard);
        for (const Aabb& box : moved) {
            Vec2 lo(1e30), hi(-1e30);
            for (const Vec3& c : box.corners()) {
                const Vec4 p = clipFromWorld * Vec4(c, 1.0);
                lo = glm::min(lo, Vec2(p) / p.w), hi = glm::max(hi, Vec2(p) / p.w);
            }
            if (hi.x >= -1.0 && lo.x <= 1.0 && hi.y >= -1.0 && lo.y <= 1.0) expected.insert(k);
        }
    }
    ASSERT_FALSE(expected.empty());
    ASSERT_LT(expected.size(), requested.size() / 2) << "the boxes cover the view: the test checks little";
    std::set<int> levelsHit;
    for (const Key& k : expected) levelsHit.insert(exponentOf(k));
    EXPECT_EQ(levelsHit.size(), setup.views.size()); // every level
    const std::vector<Key> redrawn = frame(cache, setup, 0, moved);
    EXPECT_EQ(std::set<Key>(redrawn.begin(), redrawn.end()), expected);
    EXPECT_TRUE(frame(cache, setup, 0).empty()); // and then cached again
}

TEST(VirtualPageCacheTest, ATinyPoolFallsBackToCoarserLevelsAndSaysSo) {
    const ShadowSetup setup = virtualSetup();
    std::set<Key> requested;
    requestBits(setup, setup.views, &requested);
    constexpr int kPool = 6;
    VirtualPageCache cache;
    cache.configure(kPool, kGuard);
    const std::vector<Key> drawn = frame(cache, setup, 0);
    EXPECT_EQ(drawn.size(), size_t(kPool));
    EXPECT_EQ(cache.stats().poolPages, kPool);
    EXPECT_EQ(cache.stats().pagesResident, kPool);
    EXPECT_EQ(cache.stats().pagesFellBack, static_cast<int>(requested.size()) - kPool);
    // The pages allocated are the coarsest requested: every receiver's fallback first.
    std::vector<int> exponents;
    for (const Key& k : requested) exponents.push_back(exponentOf(k));
    std::ranges::sort(exponents, std::greater<>());
    for (const Key& k : drawn) EXPECT_GE(exponentOf(k), exponents[kPool - 1]);
    // The table points only at the pool's slots, once each.
    std::set<uint32_t> slots;
    for (const uint32_t entry : cache.pageTable()) {
        if (entry == 0) continue;
        EXPECT_LE(entry, uint32_t(kPool));
        EXPECT_TRUE(slots.insert(entry).second);
    }
    EXPECT_EQ(slots.size(), size_t(kPool));
}

namespace {

// The pages a page table shows, each with its entry's index and its slot + 1.
std::map<Key, std::pair<size_t, uint32_t>> shownEntries(const VirtualPageCache& cache) {
    std::map<Key, std::pair<size_t, uint32_t>> entries;
    const ShadowSetup& shown = cache.shown();
    const int pages = shown.clipmap->pagesPerSide();
    const auto table = cache.pageTable();
    for (size_t l = 0; l < shown.views.size(); ++l) {
        const ClipmapLevel& level = std::get<ClipmapLevel>(shown.views[l].warp);
        for (int64_t y = 0; y < pages; ++y)
            for (int64_t x = 0; x < pages; ++x)
                if (const size_t i = tableIndexOf(shown, l, x, y); table[i] != 0)
                    entries[{level.exponent, level.firstPageX + x, level.firstPageY + y}] = {i, table[i]};
    }
    return entries;
}

// The keys of the pages a page table shows (slot numbers differ between two caches).
std::set<Key> shownKeys(const VirtualPageCache& cache) {
    std::set<Key> keys;
    for (const auto& [key, entry] : shownEntries(cache)) keys.insert(key);
    return keys;
}

} // namespace

TEST(VirtualPageCacheTest, MarksReadTwoFramesLateRequestThePagesTheirFrameMarkedWhereverTheWindowMoved) {
    // The eye walks 6 m a frame, then stands. One cache reads each frame's own marks; the other
    // reads, from the third frame on, the marks of two frames before, as a GPU returns them
    // without a wait. The late cache draws exactly the pages those earlier frames marked —
    // pages named in the grid, not in the window that has moved on since — and, two frames
    // after the eye stops, shows the same pages as the cache that waited. Where the marks of two
    // frames before do not apply, the frame reads its own, as the GPU path then waits.
    constexpr int kWalk = 6, kStand = 4, kLate = 2;
    const auto eyeAt = [&](int f) { return Vec3(6.0 * std::min(f, kWalk), 1.8, -2.0 * std::min(f, kWalk)); };
    VirtualPageCache waiting, late;
    waiting.configure(4096, kGuard);
    late.configure(4096, kGuard);
    std::vector<std::vector<uint32_t>> marks; // per frame, in that frame's windows
    std::vector<int64_t> markedIn;
    std::set<Key> drawnLate, expectedLate;
    std::set<int64_t> firstPagesX; // the finest window's corner, to see it move
    int ownMarks = 0;
    for (int f = 0; f < kWalk + kStand; ++f) {
        const ShadowSetup setup = virtualSetup(Vec3(0.5, 1.0, 0.3), eyeAt(f));
        const PageContent content = pageContentOf(*setup.clipmap, kGuard);
        waiting.beginFrame(setup, content, 0, eyeAt(f));
        waiting.request(requestBits(setup, setup.views), {}, {});
        waiting.rendered();

        const auto& windows = late.beginFrame(setup, content, 0, eyeAt(f));
        marks.push_back(requestBits(setup, windows.standing));
        markedIn.push_back(late.frame());
        firstPagesX.insert(std::get<ClipmapLevel>(windows.standing[0].warp).firstPageX);
        // The first frames have nothing earlier, and a frame with a level its source frame did not
        // have (the eye walked to where the clipmap needs one more) cannot use it: their own.
        int source = f < kLate ? f : f - kLate;
        if (!late.marksApply(markedIn[size_t(source)])) source = f;
        ownMarks += source == f;
        // The pages the source frame marked, inside this frame's windows.
        const ShadowSetup then = virtualSetup(Vec3(0.5, 1.0, 0.3), eyeAt(source));
        std::set<Key> marked;
        requestBits(then, then.views, &marked);
        const int pages = setup.clipmap->pagesPerSide();
        for (const Key& k : marked)
            for (const ShadowView& w : windows.standing) {
                const ClipmapLevel& level = std::get<ClipmapLevel>(w.warp);
                const int64_t x = std::get<1>(k) - level.firstPageX, y = std::get<2>(k) - level.firstPageY;
                if (level.exponent == std::get<0>(k) && x >= 0 && y >= 0 && x < pages && y < pages)
                    expectedLate.insert(k);
            }
        late.request(marks[size_t(source)], {}, {}, markedIn[size_t(source)]);
        EXPECT_EQ(late.stats().marksAge, f - source);
        for (const auto& p : late.pagesToRender()) drawnLate.insert(keyOf(p.key));
        late.rendered();
    }
    // Two frames had no earlier marks; the level added on the walk makes two more wait.
    EXPECT_EQ(ownMarks, 4);
    ASSERT_GE(firstPagesX.size(), 4u) << "the windows did not move: the test checks little";
    EXPECT_EQ(drawnLate, expectedLate);
    EXPECT_EQ(shownKeys(late), shownKeys(waiting));
    EXPECT_FALSE(shownKeys(late).empty());
}

TEST(VirtualPageCacheTest, MarksFromBeforeTheSunMovedDoNotApplyAndRequestNothing) {
    const ShadowSetup sunA = virtualSetup(), sunB = virtualSetup(Vec3(-0.4, 1.0, 0.2));
    for (const int budget : {0, 4}) {
        VirtualPageCache cache;
        cache.configure(4096, kGuard);
        const auto& windows = cache.beginFrame(sunA, pageContentOf(*sunA.clipmap, kGuard), budget, Vec3(0.0, 1.8, 0.0));
        const std::vector<uint32_t> marksA = requestBits(sunA, windows.standing);
        const int64_t frameA = cache.frame();
        cache.request(marksA, {}, {});
        cache.rendered();
        cache.beginFrame(sunA, pageContentOf(*sunA.clipmap, kGuard), budget, Vec3(0.0, 1.8, 0.0));
        EXPECT_TRUE(cache.marksApply(frameA)) << "the same sun, the same levels";
        cache.request({}, {}, {});
        cache.rendered();
        cache.beginFrame(sunB, pageContentOf(*sunB.clipmap, kGuard), budget, Vec3(0.0, 1.8, 0.0));
        EXPECT_FALSE(cache.marksApply(frameA)) << "budget " << budget;
        EXPECT_TRUE(cache.marksApply(cache.frame()));
        cache.request(marksA, {}, {}, frameA);
        EXPECT_EQ(cache.stats().pagesRequested, 0) << "budget " << budget;
        EXPECT_EQ(cache.stats().marksAge, -1);
        EXPECT_TRUE(cache.pagesToRender().empty()) << "budget " << budget;
        cache.rendered();
    }
    VirtualPageCache cache;
    cache.configure(64, kGuard);
    for (int f = 0; f < VirtualPageCache::kMarkedFramesKept + 1; ++f)
        cache.beginFrame(sunA, pageContentOf(*sunA.clipmap, kGuard), 0, Vec3(0.0, 1.8, 0.0));
    EXPECT_FALSE(cache.marksApply(1)) << "a frame no longer kept";
    EXPECT_TRUE(cache.marksApply(2));
}

TEST(VirtualPageCacheTest, TheTableChangesAreExactlyTheEntriesThatDifferFromTheLastTable) {
    // What a GPU copy of the table must take again: compared here with the test's own copy of the
    // last table, over a first frame, still frames, a moving eye and a new sun.
    VirtualPageCache cache;
    cache.configure(4096, kGuard);
    std::vector<uint32_t> last;
    size_t changedEntries = 0;
    const auto check = [&](const ShadowSetup& setup, const char* what) {
        frame(cache, setup, 0);
        const auto table = cache.pageTable();
        EXPECT_EQ(cache.tableRebuilt(), last.size() != table.size()) << what;
        std::vector<std::pair<uint32_t, uint32_t>> expected, listed;
        for (size_t i = 0; i < table.size() && last.size() == table.size(); ++i)
            if (table[i] != last[i]) expected.emplace_back(uint32_t(i), table[i]);
        for (const auto& change : cache.tableChanges()) listed.emplace_back(change.index, change.entry);
        EXPECT_EQ(listed, expected) << what;
        changedEntries += listed.size();
        last.assign(table.begin(), table.end());
        return listed.size();
    };
    const ShadowSetup setup = virtualSetup();
    check(setup, "first frame");
    EXPECT_TRUE(cache.tableRebuilt());
    EXPECT_TRUE(cache.tableChanges().empty()) << "a rebuilt table lists nothing: all of it is new";
    for (int i = 0; i < 2; ++i) EXPECT_EQ(check(setup, "still"), 0u);
    for (const double x : {0.4, 3.0, 9.0, 40.0}) check(virtualSetup(Vec3(0.5, 1.0, 0.3), Vec3(x, 1.8, 0.0)), "moved");
    check(virtualSetup(Vec3(-0.4, 1.0, 0.2)), "new sun");
    EXPECT_GT(changedEntries, 0u) << "nothing changed: the check is empty";
}

TEST(VirtualPageCacheTest, AMovingWindowKeepsEveryPageItStillCoversAtTheSameEntry) {
    // The table is toroidal (pageTableCellOf): as the eye walks, a page that stays in its level's
    // window keeps its entry — the same index, the same slot — so a frame changes the entries of
    // the pages that came or went, never the rest of the level. With the window's first page at
    // entry 0 (as the table was once addressed) every kept page would move with each step.
    VirtualPageCache cache;
    cache.configure(4096, kGuard);
    frame(cache, virtualSetup(), 0);
    auto before = shownEntries(cache);
    size_t kept = 0, stepsThatMovedAWindow = 0;
    for (const double x : {0.4, 3.0, 9.0, 17.0, 40.0}) {
        const ShadowSetup moved = virtualSetup(Vec3(0.5, 1.0, 0.3), Vec3(x, 1.8, 0.0));
        const ShadowSetup previous = cache.shown();
        frame(cache, moved, 0);
        const auto after = shownEntries(cache);
        bool windowMoved = false;
        for (size_t l = 0; l < std::min(moved.views.size(), previous.views.size()); ++l)
            windowMoved |= std::get<ClipmapLevel>(moved.views[l].warp).firstPageX !=
                           std::get<ClipmapLevel>(previous.views[l].warp).firstPageX;
        stepsThatMovedAWindow += windowMoved;
        size_t keptNow = 0;
        for (const auto& [key, entry] : after)
            if (const auto it = before.find(key); it != before.end()) {
                EXPECT_EQ(entry, it->second) << "eye at x = " << x << ": page " << std::get<1>(key) << ", "
                                             << std::get<2>(key) << " of level 2^" << exponentOf(key);
                ++keptNow;
            }
        // So an entry changes only where a page went or came: at most one change for each.
        const size_t went = before.size() - keptNow, came = after.size() - keptNow;
        EXPECT_LE(cache.tableChanges().size(), went + came) << "eye at x = " << x;
        EXPECT_GT(came, 0u) << "eye at x = " << x << ": no page came";
        kept += keptNow;
        before = after;
    }
    EXPECT_GE(stepsThatMovedAWindow, 3u) << "the windows hardly moved: the test checks little";
    EXPECT_GT(kept, 100u);
}
