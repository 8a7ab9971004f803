#include "virtual_pages.h"

#include "gl_shaders.h"
#include "program.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <string>

namespace shadowkit::gl {
namespace {

constexpr int64_t kPoolTexelBudget = int64_t(1) << 24; // 64 MiB of 32-bit depth

const core::ClipmapLevel& levelOf(const core::ShadowView& view) { return std::get<core::ClipmapLevel>(view.warp); }

} // namespace

PageContent pageContentOf(const core::VirtualClipmap& clipmap, int guardTexels, const core::BiasSettings& bias,
                          const RenderSettings& settings) {
    return {.lightFromWorldRotation = clipmap.lightFromWorldRotation,
            .wsGridOrigin = clipmap.wsGridOrigin,
            .zNear = clipmap.zNear,
            .zFar = clipmap.zFar,
            .pageTexels = clipmap.pageTexels,
            .guardTexels = guardTexels,
            .slopeBias = static_cast<float>(bias.slope),
            .constantBias = static_cast<float>(bias.constant),
            .cull = static_cast<int>(bias.cull),
            .lod = settings.lod,
            .lodTexelError = settings.lodTexelError};
}

core::Status validateVirtualSettings(const RenderSettings& settings) {
    if (settings.virtualPoolPages < 0)
        return core::fieldError("virtual.pool_pages", "must be >= 0 (0: as many as fit 64 MiB), got " +
                                                          std::to_string(settings.virtualPoolPages));
    if (!(settings.virtualBlendBand >= 0.0f && settings.virtualBlendBand < 1.0f))
        return core::fieldError("virtual.blend_band", "must be a fraction in [0, 1)");
    if (settings.virtualPageBudget < 0)
        return core::fieldError("virtual.page_budget", "must be >= 0 (0: every page requested), got " +
                                                           std::to_string(settings.virtualPageBudget));
    return core::Ok{};
}

core::Result<std::unique_ptr<VirtualPages>> VirtualPages::create() {
    auto pages = std::unique_ptr<VirtualPages>(new VirtualPages);
    auto program = buildComputeProgram("virtual page marking", {shaders::kVirtualMarkComp});
    if (!program) return program.errorInfo();
    if (auto s = checkUniformBlock(*program, "virtual page marking", "VirtualMark", sizeof(VirtualMarkUniforms),
                                   virtualMarkFields());
        !s)
        return s.errorInfo();
    pages->m_mark = std::move(program).value();
    pages->m_markUniforms = createBuffer(nullptr, sizeof(VirtualMarkUniforms));
    pages->m_mapsUniforms = createBuffer(nullptr, sizeof(VirtualMapsUniforms));
    const VirtualMapsUniforms disabled{};
    pages->m_disabledUniforms = createBuffer(&disabled, sizeof disabled);
    return pages;
}

core::Status VirtualPages::configure(int slots, int pageTexels, int guardTexels) {
    const int slotTexels = pageTexels + 2 * guardTexels;
    if (slots == 0) slots = static_cast<int>(kPoolTexelBudget / (int64_t(slotTexels) * slotTexels));
    if (slots == static_cast<int>(m_slots.size()) && pageTexels == m_pageTexels && guardTexels == m_guardTexels)
        return core::Ok{};
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    const int perRow = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(std::max(slots, 1)))));
    const int rows = (slots + perRow - 1) / perRow;
    if (slots < 1 || int64_t(perRow) * slotTexels > maxSize || int64_t(rows) * slotTexels > maxSize)
        return core::environmentError("virtual.pool_pages: " + std::to_string(slots) + " pages of " +
                                          std::to_string(slotTexels) + "² texels do not fit a " +
                                          std::to_string(maxSize) + "² texture on this GL driver",
                                      "virtual.pool_pages");
    m_atlas = {};
    m_framebuffer = {};
    glGetError();
    m_atlas = createTexture2DArray(GL_DEPTH_COMPONENT32F, perRow * slotTexels, rows * slotTexels, 1);
    if (glGetError() == GL_OUT_OF_MEMORY)
        return core::environmentError("virtual.pool_pages: out of GPU memory for " + std::to_string(slots) + " pages",
                                      "virtual.pool_pages");
    glTextureParameteri(m_atlas.id(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(m_atlas.id(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    glTextureParameteri(m_atlas.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(m_atlas.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    m_framebuffer = createFramebuffer();
    glNamedFramebufferTextureLayer(m_framebuffer.id(), GL_DEPTH_ATTACHMENT, m_atlas.id(), 0, 0);
    glNamedFramebufferDrawBuffer(m_framebuffer.id(), GL_NONE);
    glNamedFramebufferReadBuffer(m_framebuffer.id(), GL_NONE);
    if (auto s = checkComplete(m_framebuffer, "virtual page atlas"); !s) return s;
    m_slotsPerRow = perRow;
    m_slotTexels = slotTexels;
    m_pageTexels = pageTexels;
    m_guardTexels = guardTexels;
    m_atlasTexels = {perRow * slotTexels, rows * slotTexels};
    m_slots.assign(size_t(slots), Slot{});
    m_resident.clear();
    return core::Ok{};
}

glm::ivec3 VirtualPages::slotViewport(int slot) const {
    return {(slot % m_slotsPerRow) * m_slotTexels, (slot / m_slotsPerRow) * m_slotTexels, m_slotTexels};
}

void VirtualPages::dropAll() {
    for (Slot& s : m_slots) s = Slot{};
    m_resident.clear();
}

void VirtualPages::advanceGenerations(const PageContent& content, int pageBudget) {
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
    for (int s = 0; s < static_cast<int>(m_slots.size()); ++s) {
        Slot& slot = m_slots[size_t(s)];
        if (!slot.used || slot.key.generation == m_front.id || (m_back && slot.key.generation == m_back->id)) continue;
        m_resident.erase(slot.key);
        slot = Slot{};
    }
}

core::VirtualClipmap VirtualPages::clipmapOf(const core::VirtualClipmap& current, const Generation& g) {
    core::VirtualClipmap c = current;
    c.lightFromWorldRotation = g.content.lightFromWorldRotation;
    c.wsGridOrigin = g.content.wsGridOrigin;
    c.zNear = g.content.zNear;
    c.zFar = g.content.zFar;
    return c;
}

core::ShadowView VirtualPages::levelView(const core::ShadowSetup& setup, int level, const PageContent& content,
                                         const Generation& g, const core::Vec3& wsEye) {
    if (g.content == content) return setup.views[size_t(level)];
    return core::clipmapLevelView(clipmapOf(*setup.clipmap, g), levelOf(setup.views[size_t(level)]).exponent, wsEye);
}

void VirtualPages::mark(const CameraDepthTarget& depth, const core::PerspectiveCamera& camera,
                        const core::ShadowSetup& setup, std::span<const core::ShadowView> views, double reachTexels,
                        Buffer& bits, size_t& capacity, std::vector<uint32_t>& readBack) {
    const core::VirtualClipmap& clipmap = *setup.clipmap;
    const int levels = static_cast<int>(views.size());
    const int pages = clipmap.pagesPerSide();
    VirtualMarkUniforms u{};
    u.worldFromClip = glm::mat4(glm::inverse(camera.clipFromWorld()));
    u.wsEye = glm::vec4(glm::vec3(camera.wsEye), 1.0f);
    u.wsViewForward = glm::vec4(glm::vec3(glm::normalize(camera.wsDirection)), 0.0f);
    for (int l = 0; l < levels; ++l) u.levelClipFromWorld[l] = glm::mat4(views[size_t(l)].clipFromWorld);
    u.levels = levels;
    u.firstExponent = clipmap.firstExponent;
    u.footprintPerMetre = static_cast<float>(clipmap.footprintPerMetre);
    u.lodBias = static_cast<float>(clipmap.lodBias);
    u.pagesPerSide = pages;
    u.pageTexels = clipmap.pageTexels;
    u.reachTexels = static_cast<float>(reachTexels);
    glNamedBufferSubData(m_markUniforms.id(), 0, sizeof u, &u);
    const size_t words = (size_t(levels) * pages * pages + 31) / 32;
    if (words > capacity) {
        capacity = words;
        bits = createBuffer(nullptr, words * sizeof(uint32_t));
    }
    const uint32_t zero = 0;
    glClearNamedBufferSubData(bits.id(), GL_R32UI, 0, GLsizeiptr(words * sizeof(uint32_t)), GL_RED_INTEGER,
                              GL_UNSIGNED_INT, &zero);
    glUseProgram(m_mark.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, kVirtualMarkBinding, m_markUniforms.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPageRequestBinding, bits.id());
    glBindTextureUnit(kReceiverDepthUnit, depth.viewDepth.id());
    glDispatchCompute(GLuint(depth.width + 7) / 8, GLuint(depth.height + 7) / 8, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    readBack.resize(words);
    glGetNamedBufferSubData(bits.id(), 0, GLsizeiptr(words * sizeof(uint32_t)), readBack.data());
}

void VirtualPages::appendKeys(int pagesPerSide, const core::ShadowView& view, int level,
                              const std::vector<uint32_t>& readBack, int64_t generation, std::vector<SlotKey>& keys) {
    const core::ClipmapLevel& info = levelOf(view);
    const size_t perLevel = size_t(pagesPerSide) * pagesPerSide; // at least 64: whole words per level
    const size_t first = size_t(level) * perLevel;
    for (size_t word = first / 32; word < (first + perLevel) / 32; ++word)
        for (uint32_t bits = readBack[word]; bits != 0; bits &= bits - 1) { // each set bit
            const size_t i = word * 32 + size_t(std::countr_zero(bits)) - first;
            keys.push_back({{info.exponent, info.firstPageX + int64_t(i % size_t(pagesPerSide)),
                             info.firstPageY + int64_t(i / size_t(pagesPerSide))},
                            generation});
        }
}

void VirtualPages::invalidateUnder(std::span<const core::Aabb> moved, const core::VirtualClipmap& clipmap) {
    // In the light space of each slot's generation.
    for (const core::Aabb& box : moved) {
        const core::LightRect front = core::clipmapRectOf(clipmapOf(clipmap, m_front), box.min, box.max);
        const core::LightRect newer =
            m_back ? core::clipmapRectOf(clipmapOf(clipmap, *m_back), box.min, box.max) : front;
        for (Slot& slot : m_slots) {
            if (!slot.used || !slot.valid) continue;
            const core::LightRect& r = slot.key.generation == m_front.id ? front : newer;
            const double texel = std::ldexp(1.0, slot.key.page.exponent);
            const double pageMetres = clipmap.pageTexels * texel, guard = m_guardTexels * texel;
            const double x0 = double(slot.key.page.x) * pageMetres - guard;
            const double y0 = double(slot.key.page.y) * pageMetres - guard;
            const double x1 = x0 + pageMetres + 2.0 * guard, y1 = y0 + pageMetres + 2.0 * guard;
            if (r.maxX >= x0 && r.minX <= x1 && r.maxY >= y0 && r.minY <= y1) slot.valid = false;
        }
    }
}

void VirtualPages::request(const CameraDepthTarget& depth, const core::PerspectiveCamera& camera,
                           const core::ShadowSetup& setup, const PageContent& content,
                           std::span<const core::Aabb> moved, double reachTexels, int pageBudget) {
    const Stopwatch inGl;
    ++m_frame;
    const core::VirtualClipmap& clipmap = *setup.clipmap;
    const int levels = static_cast<int>(setup.views.size());
    const int pages = clipmap.pagesPerSide();

    // 1. Generations, and each level's window as it stands (from the back generation once the
    // level switched to it, else from the front one) and, while the back is drawn, the back's.
    advanceGenerations(content, pageBudget);
    const auto switched = [&](int l) {
        return m_back &&
               std::ranges::find(m_backExponents, levelOf(setup.views[size_t(l)]).exponent) != m_backExponents.end();
    };
    bool drawingBack = false;
    ViewList standing = setup.views, back = setup.views;
    for (int l = 0; l < levels; ++l) {
        standing[size_t(l)] = levelView(setup, l, content, switched(l) ? *m_back : m_front, camera.wsEye);
        if (m_back) back[size_t(l)] = levelView(setup, l, content, *m_back, camera.wsEye);
        drawingBack |= m_back && !switched(l);
    }

    // 2. Marking: one bit per page of every level's standing window; and of the back's windows.
    mark(depth, camera, setup, standing, reachTexels, m_requestBits, m_requestCapacity, m_readBack);
    if (drawingBack)
        mark(depth, camera, setup, back, reachTexels, m_backRequestBits, m_backRequestCapacity, m_backReadBack);
    m_gl = inGl.elapsed();

    // 3. Invalidation under movers.
    invalidateUnder(moved, clipmap);

    // 4. Requests, per level; the resident ones touched first, so none of them is evicted for
    // another. Free slots come first (lastRequested −1), then the least recently requested.
    std::vector<std::vector<SlotKey>> standingKeys(static_cast<size_t>(levels)), backKeys(standingKeys.size());
    for (int l = 0; l < levels; ++l) {
        appendKeys(pages, standing[size_t(l)], l, m_readBack, switched(l) ? m_back->id : m_front.id,
                   standingKeys[size_t(l)]);
        if (drawingBack && !switched(l))
            appendKeys(pages, back[size_t(l)], l, m_backReadBack, m_back->id, backKeys[size_t(l)]);
    }
    for (const auto* lists : {&standingKeys, &backKeys})
        for (const std::vector<SlotKey>& keys : *lists)
            for (const SlotKey& key : keys)
                if (const auto it = m_resident.find(key); it != m_resident.end())
                    m_slots[size_t(it->second)].lastRequested = m_frame;
    std::vector<int> spare;
    for (int s = 0; s < static_cast<int>(m_slots.size()); ++s)
        if (m_slots[size_t(s)].lastRequested < m_frame) spare.push_back(s);
    std::stable_sort(spare.begin(), spare.end(),
                     [&](int a, int b) { return m_slots[size_t(a)].lastRequested < m_slots[size_t(b)].lastRequested; });

    // 5. What to draw, at most `pageBudget` pages, most needed first. A page is allocated only
    // when it is drawn.
    m_toRender.clear();
    size_t nextSpare = 0;
    int budgetLeft = pageBudget > 0 ? pageBudget : std::numeric_limits<int>::max();
    enum class Outcome { Valid, Drawn, NoSlot, OverBudget };
    const auto schedule = [&](const SlotKey& key) {
        const auto it = m_resident.find(key);
        if (it != m_resident.end() && m_slots[size_t(it->second)].valid) return Outcome::Valid;
        if (budgetLeft == 0) return Outcome::OverBudget;
        int s = 0;
        if (it != m_resident.end()) {
            s = it->second;
        } else {
            if (nextSpare == spare.size()) return Outcome::NoSlot;
            s = spare[nextSpare++];
            Slot& slot = m_slots[size_t(s)];
            if (slot.used) m_resident.erase(slot.key);
            slot = Slot{key, m_frame, true, false};
            m_resident.emplace(key, s);
        }
        --budgetLeft;
        const Generation& g = key.generation == m_front.id ? m_front : *m_back;
        m_toRender.push_back(
            {key.page, s, core::clipmapPageClipFromWorld(clipmapOf(clipmap, g), key.page, m_guardTexels)});
        return Outcome::Drawn;
    };
    int requested = 0, fellBack = 0, deferred = 0;
    const auto scheduleShown = [&](const std::vector<SlotKey>& keys) {
        requested += static_cast<int>(keys.size());
        for (const SlotKey& key : keys) {
            const Outcome o = schedule(key);
            fellBack += o == Outcome::NoSlot; // served by a coarser level
            deferred += o == Outcome::OverBudget;
        }
    };
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
        if (missing > budgetLeft) continue;
        switchNow[size_t(l)] = true;
        scheduleShown(keys);
    }
    // c. The levels staying on the front generation: their pages, coarsest first.
    for (int l = levels - 1; l >= 0 && drawingBack; --l)
        if (!switched(l) && !switchNow[size_t(l)]) scheduleShown(standingKeys[size_t(l)]);
    // d. What budget is left: the back generation's pages of levels still too large, finest first.
    for (int l = 0; l < levels && drawingBack && budgetLeft > 0; ++l)
        if (!switched(l) && !switchNow[size_t(l)])
            for (const SlotKey& key : backKeys[size_t(l)]) schedule(key);

    // 6. What the lookup reads: each level from the back generation if it switched (before or
    // now), else from the front; when every level has, the back generation is the front one.
    m_shown = setup;
    m_shownGeneration.assign(size_t(levels), m_front.id);
    int levelsBehind = 0;
    int64_t oldestShown = m_frame; // lastCurrent of the oldest generation a level is shown from
    for (int l = 0; l < levels; ++l) {
        const bool fromBack = m_back && (switched(l) || switchNow[size_t(l)]);
        if (switchNow[size_t(l)]) m_backExponents.push_back(levelOf(setup.views[size_t(l)]).exponent);
        const Generation& g = fromBack ? *m_back : m_front;
        m_shown.views[size_t(l)] = fromBack ? back[size_t(l)] : standing[size_t(l)];
        m_shownGeneration[size_t(l)] = g.id;
        levelsBehind += m_back && !fromBack;
        oldestShown = std::min(oldestShown, g.lastCurrent);
    }
    if (m_back && levelsBehind == 0) {
        m_front = *m_back;
        m_back.reset();
        m_backExponents.clear();
    }
    m_stats = {};
    m_stats.pagesRequested = requested;
    m_stats.pagesRendered = static_cast<int>(m_toRender.size());
    m_stats.pagesFellBack = fellBack;
    m_stats.pagesDeferred = deferred;
    m_stats.levelsBehind = levelsBehind;
    m_stats.lagFrames = static_cast<int>(m_frame - oldestShown);
    m_stats.poolPages = static_cast<int>(m_slots.size());
    m_stats.poolBytes = int64_t(m_atlasTexels.x) * m_atlasTexels.y * 4;
}

DrawStats VirtualPages::drawPages(const GpuScene& scene, const PassPrograms& programs, std::span<const PassList> lists,
                                  const Buffer& depthUniforms) const {
    DrawStats draws;
    glEnable(GL_SCISSOR_TEST);
    for (size_t i = 0; i < m_toRender.size(); ++i) {
        const glm::ivec3 v = slotViewport(m_toRender[i].slot);
        glViewport(v.x, v.y, v.z, v.z);
        glScissor(v.x, v.y, v.z, v.z);
        const float clearDepth = 1.0f;
        glClearNamedFramebufferfv(m_framebuffer.id(), GL_DEPTH, 0, &clearDepth);
        const DepthPassUniforms uniforms{.clipFromWorld = glm::mat4(m_toRender[i].clipFromWorld)};
        glNamedBufferSubData(depthUniforms.id(), 0, sizeof uniforms, &uniforms);
        draws += scene.draw(lists[i], programs, visibility::clipVolume(m_toRender[i].clipFromWorld, false));
    }
    glDisable(GL_SCISSOR_TEST);
    return draws;
}

void VirtualPages::rendered() {
    for (const PageToRender& p : m_toRender) m_slots[size_t(p.slot)].valid = true;
    // The page table: each shown level's window, slot + 1 of the valid resident pages of the
    // generation it is shown from.
    const core::ShadowSetup& setup = m_shown;
    const int levels = static_cast<int>(setup.views.size());
    const int pages = setup.clipmap->pagesPerSide();
    if (pages != m_tablePagesPerSide) {
        m_pageTable = createTexture2D(GL_R32UI, pages, pages * int(core::kMaxShadowViews));
        // An integer texture with a linear filter is incomplete, and reads as 0: "absent".
        glTextureParameteri(m_pageTable.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(m_pageTable.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        m_tablePagesPerSide = pages;
    }
    m_table.assign(size_t(pages) * pages * levels, 0u);
    int resident = 0;
    for (int s = 0; s < static_cast<int>(m_slots.size()); ++s) {
        const Slot& slot = m_slots[size_t(s)];
        if (!slot.used || !slot.valid) continue;
        ++resident;
        // Levels are consecutive exponents from the finest: a kept page of a level no longer in
        // the clipmap, of the generation the level is not shown from, or outside its level's
        // window, has no entry.
        const int l = slot.key.page.exponent - setup.clipmap->firstExponent;
        if (l < 0 || l >= levels || slot.key.generation != m_shownGeneration[size_t(l)]) continue;
        const core::ClipmapLevel& info = levelOf(setup.views[size_t(l)]);
        const int64_t x = slot.key.page.x - info.firstPageX, y = slot.key.page.y - info.firstPageY;
        if (x < 0 || y < 0 || x >= pages || y >= pages) continue;
        m_table[size_t(l) * pages * pages + size_t(y) * pages + size_t(x)] = uint32_t(s + 1);
    }
    m_stats.pagesResident = resident;
    glTextureSubImage2D(m_pageTable.id(), 0, 0, 0, pages, pages * levels, GL_RED_INTEGER, GL_UNSIGNED_INT,
                        m_table.data());
}

void VirtualPages::bind(const core::ShadowSetup& setup, float blendBand) const {
    const core::VirtualClipmap& c = *setup.clipmap;
    VirtualMapsUniforms u{};
    u.enabled = 1;
    u.levels = static_cast<int32_t>(setup.views.size());
    u.firstExponent = c.firstExponent;
    u.footprintPerMetre = static_cast<float>(c.footprintPerMetre);
    u.lodBias = static_cast<float>(c.lodBias);
    u.pagesPerSide = c.pagesPerSide();
    u.pageTexels = c.pageTexels;
    u.guardTexels = m_guardTexels;
    u.slotsPerRow = m_slotsPerRow;
    u.virtualTexels = static_cast<float>(c.virtualTexels);
    u.atlasTexels = glm::vec2(m_atlasTexels);
    u.blendBand = blendBand;
    glNamedBufferSubData(m_mapsUniforms.id(), 0, sizeof u, &u);
    glBindBufferBase(GL_UNIFORM_BUFFER, kVirtualBinding, m_mapsUniforms.id());
    glBindTextureUnit(kShadowMapUnit, m_atlas.id());
    glBindTextureUnit(kShadowDepthUnit, m_atlas.id()); // PCSS's blocker search: its stored depths
    glBindTextureUnit(kPageTableUnit, m_pageTable.id());
}

scene::Image VirtualPages::readAtlas() const {
    return m_atlas ? readDepthAsGreys(m_atlas, m_atlasTexels.x, m_atlasTexels.y, 1) : scene::Image{};
}

scene::Image VirtualPages::pageTableImage() const {
    const int levels = static_cast<int>(m_shown.views.size());
    if (!m_shown.clipmap || levels == 0 || m_table.size() != size_t(m_tablePagesPerSide) * m_tablePagesPerSide * levels)
        return {};
    // main.frag's kCascadeTint, which --cascade-colors multiplies the levels' albedo by.
    static constexpr uint8_t kTint[8][3] = {{255, 89, 89},   {89, 255, 89},  {102, 128, 255}, {255, 255, 77},
                                            {255, 102, 255}, {77, 255, 255}, {255, 179, 77},  {204, 204, 204}};
    const int pages = m_tablePagesPerSide, columns = std::min(levels, 4), gap = 2;
    const int rows = (levels + columns - 1) / columns;
    scene::Image image(columns * (pages + gap) - gap, rows * (pages + gap) - gap);
    for (int l = 0; l < levels; ++l) {
        const int x0 = (l % columns) * (pages + gap), y0 = (l / columns) * (pages + gap);
        for (int y = 0; y < pages; ++y)
            for (int x = 0; x < pages; ++x) {
                const size_t i = size_t(l) * pages * pages + size_t(y) * pages + size_t(x);
                const bool requested = i / 32 < m_readBack.size() && (m_readBack[i / 32] >> (i % 32) & 1u) != 0;
                uint8_t* p = image.pixel(x0 + x, y0 + pages - 1 - y); // light-space +y up
                const uint8_t dark[3] = {24, 24, 28}, white[3] = {255, 255, 255};
                const uint8_t* c = m_table[i] != 0 ? kTint[l % 8] : requested ? white : dark;
                p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = 255;
            }
    }
    return image;
}

void VirtualPages::bindDisabled() const {
    glBindBufferBase(GL_UNIFORM_BUFFER, kVirtualBinding, m_disabledUniforms.id());
}

void VirtualPages::setLinearFilter(bool linear) const {
    if (!m_atlas) return;
    glTextureParameteri(m_atlas.id(), GL_TEXTURE_MIN_FILTER, linear ? GL_LINEAR : GL_NEAREST);
    glTextureParameteri(m_atlas.id(), GL_TEXTURE_MAG_FILTER, linear ? GL_LINEAR : GL_NEAREST);
}

} // namespace shadowkit::gl
