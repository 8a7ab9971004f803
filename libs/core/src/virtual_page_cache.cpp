#include "shadowkit/core/virtual_page_cache.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <variant>

namespace shadowkit::core {
namespace {

const ClipmapLevel& levelOf(const ShadowView& view) { return std::get<ClipmapLevel>(view.warp); }

} // namespace

PageContent pageContentOf(const VirtualClipmap& clipmap, int guardTexels) {
    return {.lightFromWorldRotation = clipmap.lightFromWorldRotation,
            .wsGridOrigin = clipmap.wsGridOrigin,
            .zNear = clipmap.zNear,
            .zFar = clipmap.zFar,
            .pageTexels = clipmap.pageTexels,
            .guardTexels = guardTexels};
}

void VirtualPageCache::configure(int slots, int guardTexels) {
    if (slots == slotCount() && guardTexels == m_guardTexels) return;
    m_guardTexels = guardTexels;
    m_slots.assign(size_t(std::max(slots, 0)), Slot{});
    m_resident.clear();
}

void VirtualPageCache::dropAll() {
    for (Slot& s : m_slots) s = Slot{};
    m_resident.clear();
}

void VirtualPageCache::advanceGenerations(const PageContent& content, int pageBudget) {
    const auto newGeneration = [&] { return Generation{m_nextGeneration++, content, m_frame}; };
    if (m_front.id < 0 || (pageBudget == 0 && !(content == m_front.content))) {
        // Without a budget a change redraws every page this frame: nothing old is kept.
        dropAll();
        m_front = newGeneration();
        m_back.reset();
    } else if (content == m_front.content) {
        m_back.reset(); // back where the front was drawn (a sun that returned): the front serves
    } else if (!m_back) {
        m_back = newGeneration(); // the sun moves on while it is drawn: the next back takes that
    }
    if (!m_back) m_backExponents.clear();
    for (Generation* g : {&m_front, m_back ? &*m_back : nullptr})
        if (g && g->content == content) g->lastCurrent = m_frame;
    for (Slot& slot : m_slots) {
        if (!slot.used || slot.key.generation == m_front.id || (m_back && slot.key.generation == m_back->id)) continue;
        m_resident.erase(slot.key);
        slot = Slot{};
    }
}

VirtualClipmap VirtualPageCache::clipmapOf(const Generation& g) const {
    VirtualClipmap c = *m_setup.clipmap;
    c.lightFromWorldRotation = g.content.lightFromWorldRotation;
    c.wsGridOrigin = g.content.wsGridOrigin;
    c.zNear = g.content.zNear;
    c.zFar = g.content.zFar;
    return c;
}

ShadowView VirtualPageCache::levelView(int level, const Generation& g) const {
    if (g.content == m_content) return m_setup.views[size_t(level)];
    return clipmapLevelView(clipmapOf(g), levelOf(m_setup.views[size_t(level)]).exponent, m_wsEye);
}

bool VirtualPageCache::switched(int level) const {
    return m_back &&
           std::ranges::find(m_backExponents, levelOf(m_setup.views[size_t(level)]).exponent) != m_backExponents.end();
}

const VirtualPageCache::Windows& VirtualPageCache::beginFrame(const ShadowSetup& setup, const PageContent& content,
                                                              int pageBudget, const Vec3& wsEye) {
    ++m_frame;
    m_setup = setup;
    m_content = content;
    m_wsEye = wsEye;
    m_budgetLeft = pageBudget > 0 ? pageBudget : std::numeric_limits<int>::max();
    // Generations, and each level's window as it stands (from the back generation once the level
    // switched to it, else from the front one) and, while the back is drawn, the back's.
    advanceGenerations(content, pageBudget);
    m_windows = {setup.views, setup.views, false};
    for (int l = 0; l < static_cast<int>(setup.views.size()); ++l) {
        m_windows.standing[size_t(l)] = levelView(l, switched(l) ? *m_back : m_front);
        if (m_back) m_windows.back[size_t(l)] = levelView(l, *m_back);
        m_windows.drawingBack |= m_back && !switched(l);
    }
    MarkedFrame marked{.frame = m_frame,
                       .windows = m_windows,
                       .pagesPerSide = setup.clipmap->pagesPerSide(),
                       .backGeneration = m_back ? m_back->id : -1};
    for (int l = 0; l < static_cast<int>(setup.views.size()); ++l)
        marked.standingGeneration.push_back(switched(l) ? m_back->id : m_front.id);
    if (m_marked.size() == size_t(kMarkedFramesKept)) m_marked.erase(m_marked.begin());
    m_marked.push_back(std::move(marked));
    return m_windows;
}

int VirtualPageCache::MarkedFrame::levelWith(int exponent) const {
    for (size_t l = 0; l < windows.standing.size(); ++l)
        if (levelOf(windows.standing[l]).exponent == exponent) return static_cast<int>(l);
    return -1;
}

bool VirtualPageCache::MarkedFrame::serves(const MarkedFrame& now) const {
    if (pagesPerSide != now.pagesPerSide || backGeneration != now.backGeneration ||
        windows.drawingBack != now.windows.drawingBack)
        return false;
    // Every level of now, marked then, for the same generation (a level added since — the eye
    // moved to where the clipmap needs one more — has no marks: the frame needs its own).
    for (size_t l = 0; l < now.windows.standing.size(); ++l) {
        const int then = levelWith(levelOf(now.windows.standing[l]).exponent);
        if (then < 0 || standingGeneration[size_t(then)] != now.standingGeneration[l]) return false;
    }
    return true;
}

const VirtualPageCache::MarkedFrame* VirtualPageCache::markedFrame(int64_t frame) const {
    const auto it = std::ranges::find(m_marked, frame, &MarkedFrame::frame);
    return it == m_marked.end() ? nullptr : &*it;
}

bool VirtualPageCache::marksApply(int64_t marked) const {
    const MarkedFrame* then = markedFrame(marked);
    return then && !m_marked.empty() && then->serves(m_marked.back());
}

void VirtualPageCache::appendKeys(const ShadowView& window, int level, std::span<const uint32_t> bits,
                                  int64_t generation, const ShadowView& shown, std::vector<SlotKey>& keys) const {
    const ClipmapLevel& info = levelOf(window);
    const ClipmapLevel& now = levelOf(shown);
    const int pagesPerSide = m_setup.clipmap->pagesPerSide();
    const size_t perLevel = size_t(pagesPerSide) * pagesPerSide; // at least 64: whole words per level
    const size_t first = size_t(level) * perLevel;
    for (size_t word = first / 32; word < (first + perLevel) / 32 && word < bits.size(); ++word)
        for (uint32_t set = bits[word]; set != 0; set &= set - 1) { // each set bit
            const size_t i = word * 32 + size_t(std::countr_zero(set)) - first;
            const PageKey page{info.exponent, info.firstPageX + int64_t(i % size_t(pagesPerSide)),
                               info.firstPageY + int64_t(i / size_t(pagesPerSide))};
            const int64_t x = page.x - now.firstPageX, y = page.y - now.firstPageY;
            if (x >= 0 && y >= 0 && x < pagesPerSide && y < pagesPerSide) keys.push_back({page, generation});
        }
}

void VirtualPageCache::invalidateUnder(std::span<const Aabb> moved) {
    const VirtualClipmap& clipmap = *m_setup.clipmap;
    // In the light space of each slot's generation.
    for (const Aabb& box : moved) {
        const LightRect front = clipmapRectOf(clipmapOf(m_front), box.min, box.max);
        const LightRect newer = m_back ? clipmapRectOf(clipmapOf(*m_back), box.min, box.max) : front;
        for (Slot& slot : m_slots) {
            if (!slot.used || !slot.valid) continue;
            const LightRect& r = slot.key.generation == m_front.id ? front : newer;
            const double texel = std::ldexp(1.0, slot.key.page.exponent);
            const double pageMetres = clipmap.pageTexels * texel, guard = m_guardTexels * texel;
            const double x0 = double(slot.key.page.x) * pageMetres - guard;
            const double y0 = double(slot.key.page.y) * pageMetres - guard;
            const double x1 = x0 + pageMetres + 2.0 * guard, y1 = y0 + pageMetres + 2.0 * guard;
            if (r.maxX >= x0 && r.minX <= x1 && r.maxY >= y0 && r.minY <= y1) slot.valid = false;
        }
    }
}

void VirtualPageCache::touch(const LevelKeys& standing, const LevelKeys& back) {
    // The resident pages requested are touched first, so none of them is evicted for another.
    for (const LevelKeys* levels : {&standing, &back})
        for (const std::vector<SlotKey>& keys : *levels)
            for (const SlotKey& key : keys)
                if (const auto it = m_resident.find(key); it != m_resident.end())
                    m_slots[size_t(it->second)].lastRequested = m_frame;
    m_spare.clear();
    m_nextSpare = 0;
    for (int s = 0; s < slotCount(); ++s)
        if (m_slots[size_t(s)].lastRequested < m_frame) m_spare.push_back(s);
    // Free slots first (lastRequested −1), then the least recently requested.
    std::stable_sort(m_spare.begin(), m_spare.end(),
                     [&](int a, int b) { return m_slots[size_t(a)].lastRequested < m_slots[size_t(b)].lastRequested; });
}

VirtualPageCache::Outcome VirtualPageCache::schedule(const SlotKey& key) {
    // A page is allocated only when it is drawn.
    const auto it = m_resident.find(key);
    if (it != m_resident.end() && m_slots[size_t(it->second)].valid) return Outcome::Valid;
    if (m_budgetLeft == 0) return Outcome::OverBudget;
    int s = 0;
    if (it != m_resident.end()) {
        s = it->second;
    } else {
        if (m_nextSpare == m_spare.size()) return Outcome::NoSlot;
        s = m_spare[m_nextSpare++];
        Slot& slot = m_slots[size_t(s)];
        if (slot.used) m_resident.erase(slot.key);
        slot = Slot{key, m_frame, true, false};
        m_resident.emplace(key, s);
    }
    --m_budgetLeft;
    const Generation& g = key.generation == m_front.id ? m_front : *m_back;
    m_toRender.push_back({key.page, s, clipmapPageClipFromWorld(clipmapOf(g), key.page, m_guardTexels)});
    return Outcome::Drawn;
}

void VirtualPageCache::scheduleShown(const std::vector<SlotKey>& keys) {
    m_stats.pagesRequested += static_cast<int>(keys.size());
    for (const SlotKey& key : keys) {
        const Outcome o = schedule(key);
        m_stats.pagesFellBack += o == Outcome::NoSlot; // served by a coarser level
        m_stats.pagesDeferred += o == Outcome::OverBudget;
    }
}

void VirtualPageCache::request(std::span<const uint32_t> standingBits, std::span<const uint32_t> backBits,
                               std::span<const Aabb> moved, int64_t markedIn) {
    const int levels = static_cast<int>(m_setup.views.size());
    const bool drawingBack = m_windows.drawingBack;
    m_stats = {};
    invalidateUnder(moved);

    // Requests, per level, through the windows they were marked in: marksApply() holds for them
    // (the caller's check), so their levels and generations are this frame's. Marks that do not
    // apply request nothing: the frame shows what is resident.
    if (markedIn == 0) markedIn = m_frame;
    const MarkedFrame* marked = markedIn > 0 && marksApply(markedIn) ? markedFrame(markedIn) : nullptr;
    m_stats.marksAge = marked ? static_cast<int>(m_frame - markedIn) : -1;
    LevelKeys standingKeys(static_cast<size_t>(levels)), backKeys(standingKeys.size());
    for (int l = 0; l < levels && marked; ++l) {
        const int then = marked->levelWith(levelOf(m_setup.views[size_t(l)]).exponent); // ≥ 0: marksApply
        appendKeys(marked->windows.standing[size_t(then)], then, standingBits, switched(l) ? m_back->id : m_front.id,
                   m_windows.standing[size_t(l)], standingKeys[size_t(l)]);
        if (drawingBack && !switched(l))
            appendKeys(marked->windows.back[size_t(then)], then, backBits, m_back->id, m_windows.back[size_t(l)],
                       backKeys[size_t(l)]);
    }
    touch(standingKeys, backKeys);

    // What to draw, most needed first.
    m_toRender.clear();
    // a. The levels certain to be shown as they stand — all of them when no back generation is
    // drawn —, coarsest first: a receiver's fallback is served before its own page.
    for (int l = levels - 1; l >= 0; --l)
        if (!drawingBack || switched(l)) scheduleShown(standingKeys[size_t(l)]);
    // b. The back generation's levels, finest first (the finest show a moving sun's lag in the
    // most texels): a level whose remaining pages fit in what is left of the budget is drawn
    // whole and shown from the back generation in this very frame.
    std::vector<bool> switchNow(size_t(levels), false);
    for (int l = 0; l < levels && drawingBack; ++l) {
        if (switched(l)) continue;
        const auto& keys = backKeys[size_t(l)];
        const auto missing = std::ranges::count_if(keys, [&](const SlotKey& key) {
            const auto it = m_resident.find(key);
            return it == m_resident.end() || !m_slots[size_t(it->second)].valid;
        });
        if (missing > m_budgetLeft) continue;
        switchNow[size_t(l)] = true;
        scheduleShown(keys);
    }
    // c. The levels staying on the front generation: their pages, coarsest first.
    for (int l = levels - 1; l >= 0 && drawingBack; --l)
        if (!switched(l) && !switchNow[size_t(l)]) scheduleShown(standingKeys[size_t(l)]);
    // d. What budget is left: the back generation's pages of levels still too large, finest first.
    for (int l = 0; l < levels && drawingBack && m_budgetLeft > 0; ++l)
        if (!switched(l) && !switchNow[size_t(l)])
            for (const SlotKey& key : backKeys[size_t(l)]) schedule(key);
    decideShown(switchNow);
}

void VirtualPageCache::decideShown(const std::vector<bool>& switchNow) {
    // What the lookup reads: each level from the back generation if it switched (before or now),
    // else from the front; when every level has, the back generation is the front one.
    const int levels = static_cast<int>(m_setup.views.size());
    m_shown = m_setup;
    m_shownGeneration.assign(size_t(levels), m_front.id);
    int levelsBehind = 0;
    int64_t oldestShown = m_frame; // lastCurrent of the oldest generation a level is shown from
    for (int l = 0; l < levels; ++l) {
        const bool fromBack = m_back && (switched(l) || switchNow[size_t(l)]);
        if (switchNow[size_t(l)]) m_backExponents.push_back(levelOf(m_setup.views[size_t(l)]).exponent);
        const Generation& g = fromBack ? *m_back : m_front;
        m_shown.views[size_t(l)] = fromBack ? m_windows.back[size_t(l)] : m_windows.standing[size_t(l)];
        m_shownGeneration[size_t(l)] = g.id;
        levelsBehind += m_back && !fromBack;
        oldestShown = std::min(oldestShown, g.lastCurrent);
    }
    if (m_back && levelsBehind == 0) {
        m_front = *m_back;
        m_back.reset();
        m_backExponents.clear();
    }
    m_stats.pagesRendered = static_cast<int>(m_toRender.size());
    m_stats.levelsBehind = levelsBehind;
    m_stats.lagFrames = static_cast<int>(m_frame - oldestShown);
    m_stats.poolPages = slotCount();
}

void VirtualPageCache::rendered() {
    for (const PageToRender& p : m_toRender) m_slots[size_t(p.slot)].valid = true;
    // The page table: each shown level's window, slot + 1 of the valid resident pages of the
    // generation it is shown from.
    const int levels = static_cast<int>(m_shown.views.size());
    const int pages = m_shown.clipmap->pagesPerSide();
    std::swap(m_table, m_previousTable);
    m_table.assign(size_t(pages) * pages * levels, 0u);
    int resident = 0;
    for (int s = 0; s < slotCount(); ++s) {
        const Slot& slot = m_slots[size_t(s)];
        if (!slot.used || !slot.valid) continue;
        ++resident;
        // Levels are consecutive exponents from the finest: a kept page of a level no longer in
        // the clipmap, of the generation the level is not shown from, or outside its level's
        // window, has no entry.
        const int l = slot.key.page.exponent - m_shown.clipmap->firstExponent;
        if (l < 0 || l >= levels || slot.key.generation != m_shownGeneration[size_t(l)]) continue;
        const ClipmapLevel& info = levelOf(m_shown.views[size_t(l)]);
        const int64_t x = slot.key.page.x - info.firstPageX, y = slot.key.page.y - info.firstPageY;
        if (x < 0 || y < 0 || x >= pages || y >= pages) continue;
        const PageTableCell cell = pageTableCellOf(slot.key.page.x, slot.key.page.y, pages);
        m_table[size_t(l) * pages * pages + size_t(cell.y) * pages + size_t(cell.x)] = uint32_t(s + 1);
    }
    m_stats.pagesResident = resident;
    // What changed since the last table: with the same shape (the same size and pages a side, so
    // the same level count) the entries that differ; else all of it.
    m_tableRebuilt = m_previousTable.size() != m_table.size() || pages != m_tablePagesPerSide;
    m_tableChanges.clear();
    for (size_t i = 0; !m_tableRebuilt && i < m_table.size(); ++i)
        if (m_table[i] != m_previousTable[i]) m_tableChanges.push_back({uint32_t(i), m_table[i]});
    m_tablePagesPerSide = pages;
}

} // namespace shadowkit::core
