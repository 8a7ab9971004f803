#include "virtual_pages.h"

#include "gl_shaders.h"
#include "program.h"

#include <algorithm>
#include <bit>
#include <cmath>
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

std::vector<core::PageKey> VirtualPages::readRequests(const core::ShadowSetup& setup) const {
    // Coarsest level first: a receiver's fallback is allocated before its own page.
    const int pages = setup.clipmap->pagesPerSide();
    const size_t perLevel = size_t(pages) * pages; // at least 64: whole words per level
    std::vector<core::PageKey> keys;
    for (int level = static_cast<int>(setup.views.size()) - 1; level >= 0; --level) {
        const core::ClipmapLevel& info = levelOf(setup.views[size_t(level)]);
        const size_t first = size_t(level) * perLevel;
        for (size_t word = first / 32; word < (first + perLevel) / 32; ++word)
            for (uint32_t bits = m_readBack[word]; bits != 0; bits &= bits - 1) { // each set bit
                const size_t i = word * 32 + size_t(std::countr_zero(bits)) - first;
                keys.push_back({info.exponent, info.firstPageX + int64_t(i % size_t(pages)),
                                info.firstPageY + int64_t(i / size_t(pages))});
            }
    }
    return keys;
}

void VirtualPages::request(const CameraDepthTarget& depth, const core::PerspectiveCamera& camera,
                           const core::ShadowSetup& setup, const PageContent& content,
                           std::span<const core::Aabb> moved, double reachTexels) {
    const Stopwatch inGl;
    ++m_frame;
    const core::VirtualClipmap& clipmap = *setup.clipmap;
    const int levels = static_cast<int>(setup.views.size());
    const int pages = clipmap.pagesPerSide();

    // 1. Marking: one bit per page of every level's window.
    VirtualMarkUniforms u{};
    u.worldFromClip = glm::mat4(glm::inverse(camera.clipFromWorld()));
    u.wsEye = glm::vec4(glm::vec3(camera.wsEye), 1.0f);
    u.wsViewForward = glm::vec4(glm::vec3(glm::normalize(camera.wsDirection)), 0.0f);
    for (int l = 0; l < levels; ++l) u.levelClipFromWorld[l] = glm::mat4(setup.views[size_t(l)].clipFromWorld);
    u.levels = levels;
    u.firstExponent = clipmap.firstExponent;
    u.footprintPerMetre = static_cast<float>(clipmap.footprintPerMetre);
    u.lodBias = static_cast<float>(clipmap.lodBias);
    u.pagesPerSide = pages;
    u.pageTexels = clipmap.pageTexels;
    u.reachTexels = static_cast<float>(reachTexels);
    glNamedBufferSubData(m_markUniforms.id(), 0, sizeof u, &u);
    const size_t words = (size_t(levels) * pages * pages + 31) / 32;
    if (words > m_requestCapacity) {
        m_requestCapacity = words;
        m_requestBits = createBuffer(nullptr, words * sizeof(uint32_t));
    }
    const uint32_t zero = 0;
    glClearNamedBufferSubData(m_requestBits.id(), GL_R32UI, 0, GLsizeiptr(words * sizeof(uint32_t)), GL_RED_INTEGER,
                              GL_UNSIGNED_INT, &zero);
    glUseProgram(m_mark.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, kVirtualMarkBinding, m_markUniforms.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPageRequestBinding, m_requestBits.id());
    glBindTextureUnit(kReceiverDepthUnit, depth.viewDepth.id());
    glDispatchCompute(GLuint(depth.width + 7) / 8, GLuint(depth.height + 7) / 8, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    m_readBack.resize(words);
    glGetNamedBufferSubData(m_requestBits.id(), 0, GLsizeiptr(words * sizeof(uint32_t)), m_readBack.data());
    m_gl = inGl.elapsed();

    // 2. Invalidation: everything when the depth would differ, else the pages under movers.
    if (!(content == m_content)) {
        dropAll();
        m_content = content;
    }
    for (const core::Aabb& box : moved) {
        const core::LightRect r = core::clipmapRectOf(clipmap, box.min, box.max);
        for (Slot& slot : m_slots) {
            if (!slot.used || !slot.valid) continue;
            const double texel = std::ldexp(1.0, slot.key.exponent);
            const double pageMetres = clipmap.pageTexels * texel, guard = m_guardTexels * texel;
            const double x0 = double(slot.key.x) * pageMetres - guard, y0 = double(slot.key.y) * pageMetres - guard;
            const double x1 = x0 + pageMetres + 2.0 * guard, y1 = y0 + pageMetres + 2.0 * guard;
            if (r.maxX >= x0 && r.minX <= x1 && r.maxY >= y0 && r.minY <= y1) slot.valid = false;
        }
    }

    // 3. Allocation: requested pages already resident are kept (touched first, so none of them
    // is evicted for another), the others take free slots, then the least recently requested.
    const std::vector<core::PageKey> requested = readRequests(setup);
    std::vector<core::PageKey> missing;
    for (const core::PageKey& key : requested) {
        const auto it = m_resident.find(key);
        if (it == m_resident.end())
            missing.push_back(key);
        else
            m_slots[size_t(it->second)].lastRequested = m_frame;
    }
    std::vector<int> spare;
    for (int s = 0; s < static_cast<int>(m_slots.size()); ++s)
        if (m_slots[size_t(s)].lastRequested < m_frame) spare.push_back(s);
    // Free slots first (lastRequested −1), then the oldest; taken from the front.
    std::stable_sort(spare.begin(), spare.end(),
                     [&](int a, int b) { return m_slots[size_t(a)].lastRequested < m_slots[size_t(b)].lastRequested; });
    size_t next = 0;
    int fellBack = 0;
    for (const core::PageKey& key : missing) {
        if (next == spare.size()) {
            ++fellBack;
            continue;
        }
        const int s = spare[next++];
        Slot& slot = m_slots[size_t(s)];
        if (slot.used) m_resident.erase(slot.key);
        slot = Slot{key, m_frame, true, false};
        m_resident.emplace(key, s);
    }

    // 4. What to draw: every requested, resident page not valid.
    m_toRender.clear();
    for (const core::PageKey& key : requested) {
        const auto it = m_resident.find(key);
        if (it == m_resident.end() || m_slots[size_t(it->second)].valid) continue;
        m_toRender.push_back({key, it->second, core::clipmapPageClipFromWorld(clipmap, key, m_guardTexels)});
    }
    m_stats = {};
    m_stats.pagesRequested = static_cast<int>(requested.size());
    m_stats.pagesRendered = static_cast<int>(m_toRender.size());
    m_stats.pagesFellBack = fellBack;
    m_stats.poolPages = static_cast<int>(m_slots.size());
    m_stats.poolBytes = int64_t(m_atlasTexels.x) * m_atlasTexels.y * 4;
}

DrawStats VirtualPages::drawPages(const GpuScene& scene, std::span<const PassList> lists,
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
        draws += scene.draw(lists[i], visibility::clipVolume(m_toRender[i].clipFromWorld, false));
    }
    glDisable(GL_SCISSOR_TEST);
    return draws;
}

void VirtualPages::rendered(const core::ShadowSetup& setup) {
    for (const PageToRender& p : m_toRender) m_slots[size_t(p.slot)].valid = true;
    // The page table: each level's window, slot + 1 of its valid resident pages.
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
        // the clipmap, or outside its level's window, has no entry.
        const int l = slot.key.exponent - setup.clipmap->firstExponent;
        if (l < 0 || l >= levels) continue;
        const core::ClipmapLevel& info = levelOf(setup.views[size_t(l)]);
        const int64_t x = slot.key.x - info.firstPageX, y = slot.key.y - info.firstPageY;
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
    glBindTextureUnit(kPageTableUnit, m_pageTable.id());
}

scene::Image VirtualPages::readAtlas() const {
    return m_atlas ? readDepthAsGreys(m_atlas, m_atlasTexels.x, m_atlasTexels.y, 1) : scene::Image{};
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
