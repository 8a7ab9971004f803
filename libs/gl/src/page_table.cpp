#include "page_table.h"

#include "gl_shaders.h"
#include "program.h"
#include "uniforms.h"

#include "shadowkit/gl/read_backs.h"

#include <bit>
#include <cstddef>

namespace shadowkit::gl {
namespace {

// page_table_update.comp's uniforms (explicit locations) and its entries, as its uvec2s.
constexpr GLint kChangeCountLocation = 0, kPagesPerSideLocation = 1;
static_assert(sizeof(PageTable::Change) == 2 * sizeof(uint32_t) &&
              offsetof(PageTable::Change, entry) == sizeof(uint32_t));

} // namespace

core::Result<std::unique_ptr<PageTable>> PageTable::create() {
    auto table = std::unique_ptr<PageTable>(new PageTable);
    auto program = buildComputeProgram("virtual page table update", {shaders::kPageTableUpdateComp});
    if (!program) return program.errorInfo();
    table->m_update = std::move(program).value();
    return table;
}

void PageTable::update(std::span<const uint32_t> table, int pagesPerSide, bool rebuilt,
                       std::span<const Change> changes) {
    const int levels = static_cast<int>(table.size() / (size_t(pagesPerSide) * size_t(pagesPerSide)));
    const bool created = pagesPerSide != m_pagesPerSide;
    if (created) {
        m_texture = createTexture2D(GL_R32UI, pagesPerSide, pagesPerSide * int(core::kMaxShadowViews));
        // An integer texture with a linear filter is incomplete, and reads as 0: "absent".
        glTextureParameteri(m_texture.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(m_texture.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        m_pagesPerSide = pagesPerSide;
    }
    // Level l's entries are rows l × pagesPerSide … of the texture.
    m_bytesUploaded = 0;
    if (created || rebuilt || changes.size_bytes() >= table.size_bytes()) {
        glTextureSubImage2D(m_texture.id(), 0, 0, 0, pagesPerSide, pagesPerSide * levels, GL_RED_INTEGER,
                            GL_UNSIGNED_INT, table.data());
        m_bytesUploaded = int64_t(table.size_bytes());
        detail::countUpload(m_bytesUploaded);
        return;
    }
    if (changes.empty()) return;
    if (changes.size_bytes() > m_changesCapacity) {
        m_changesCapacity = std::bit_ceil(changes.size_bytes()); // grown in steps, not every frame
        m_changes = createBuffer(nullptr, m_changesCapacity, true);
    }
    uploadToBuffer(m_changes.id(), 0, GLsizeiptr(changes.size_bytes()), changes.data());
    m_bytesUploaded = int64_t(changes.size_bytes());
    glUseProgram(m_update.id());
    glProgramUniform1ui(m_update.id(), kChangeCountLocation, GLuint(changes.size()));
    glProgramUniform1ui(m_update.id(), kPagesPerSideLocation, GLuint(pagesPerSide));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPageTableChangesBinding, m_changes.id());
    glBindImageTexture(kPageTableImageUnit, m_texture.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32UI);
    dispatchCompute(GLuint(changes.size() + 63) / 64, 1, 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT); // the lookup reads the table next
}

std::vector<uint32_t> PageTable::read(int levels) const {
    if (!m_texture || levels <= 0) return {};
    std::vector<uint32_t> all(size_t(m_pagesPerSide) * m_pagesPerSide * core::kMaxShadowViews);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT); // the compute pass's writes, before a read of the texture
    detail::countReadBack();
    readTexture(m_texture.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, GLsizei(all.size() * sizeof(uint32_t)), all.data());
    all.resize(size_t(m_pagesPerSide) * m_pagesPerSide * size_t(levels));
    return all;
}

} // namespace shadowkit::gl
