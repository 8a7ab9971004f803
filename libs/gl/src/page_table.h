// Virtual shadow maps' page table on the GPU (virtual_pages.h): an R32UI texture, pagesPerSide
// wide and pagesPerSide rows a level, kept equal to core::VirtualPageCache::pageTable(). A new
// table goes up whole; after that, the entries the cache lists as changed are written in place by
// a compute pass (page_table_update.comp), eight bytes each. The table is addressed toroidally
// (core::pageTableCellOf), so a moving window changes the entries of the pages that came and
// went, not its level: a flythrough frame moves a few hundred bytes, not the whole table.
#pragma once

#include "gl_object.h"

#include "shadowkit/core/result.h"
#include "shadowkit/core/virtual_page_cache.h"

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace shadowkit::gl {

class PageTable {
public:
    static core::Result<std::unique_ptr<PageTable>> create();

    using Change = core::VirtualPageCache::TableChange;
    // Makes the texture equal `table` (levels × pagesPerSide² entries, level after level,
    // row-major): the whole of it when `rebuilt`, the texture is new (another pagesPerSide) or
    // the changes outweigh it; else `changes`, which must be every entry that differs from the
    // table last given, once each (two writes of one texel would race).
    void update(std::span<const uint32_t> table, int pagesPerSide, bool rebuilt, std::span<const Change> changes);
    const Texture& texture() const { return m_texture; }
    // What the last update() uploaded: 8 bytes a change, the table's size when whole, 0 for none.
    int64_t bytesUploaded() const { return m_bytesUploaded; }
    // The texture's first `levels` levels as they are on the GPU (a read-back: tests, debugging).
    std::vector<uint32_t> read(int levels) const;

private:
    PageTable() = default;
    Program m_update;
    Texture m_texture;
    int m_pagesPerSide = 0;
    int64_t m_bytesUploaded = 0;
    Buffer m_changes;             // this frame's changes, for the compute pass
    size_t m_changesCapacity = 0; // bytes
};

} // namespace shadowkit::gl
