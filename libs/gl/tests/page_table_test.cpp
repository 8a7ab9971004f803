// The virtual page table on the GPU (page_table.h): after a whole upload and after changes written
// in place by its compute pass, the texture read back equals the table it was given — the
// property every virtual frame's lookup rests on, checked entry by entry here since a missed
// change shows in an image only where a page's depth differs from its fallback's — and the
// changes move eight bytes each, not the table.
#include "headless_gl_test.h"

#include "page_table.h"

#include "shadowkit/gl/read_backs.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

using namespace shadowkit;

namespace {

class PageTableTest : public gl::testing::HeadlessGlTest {};

// A table's entries as the cache makes them: slot + 1 of a page, or 0, from a fixed sequence.
std::vector<uint32_t> someTable(int pagesPerSide, int levels, uint32_t seed) {
    std::vector<uint32_t> table(size_t(pagesPerSide) * pagesPerSide * levels);
    for (uint32_t& entry : table) {
        seed = seed * 1664525u + 1013904223u;
        entry = (seed >> 28) < 6 ? (seed >> 8) % 4096u + 1u : 0u; // about 6 in 16 resident
    }
    return table;
}

// How many entries of the texture differ from `table`, and where the first does (−1: none).
std::string differences(const std::vector<uint32_t>& gpu, const std::vector<uint32_t>& table) {
    if (gpu.size() != table.size())
        return "read " + std::to_string(gpu.size()) + " entries of " + std::to_string(table.size());
    size_t differ = 0, first = 0;
    for (size_t i = table.size(); i-- > 0;)
        if (gpu[i] != table[i]) ++differ, first = i;
    if (differ == 0) return "";
    return std::to_string(differ) + " entries differ, the first " + std::to_string(first) + ": " +
           std::to_string(gpu[first]) + " on the GPU, " + std::to_string(table[first]) + " in the table";
}

} // namespace

TEST_F(PageTableTest, ChangesWrittenInPlaceLeaveTheTextureEqualToTheTableAndMoveEightBytesEach) {
    auto pageTable = gl::PageTable::create();
    ASSERT_TRUE(pageTable) << pageTable.error();
    constexpr int kPages = 32, kLevels = 5;
    std::vector<uint32_t> table = someTable(kPages, kLevels, 7u);

    gl::Traffic before = gl::trafficSoFar();
    (*pageTable)->update(table, kPages, /*rebuilt=*/true, {});
    EXPECT_EQ((gl::trafficSoFar() - before).bytesUploaded, int64_t(table.size() * sizeof(uint32_t)));
    EXPECT_EQ(differences((*pageTable)->read(kLevels), table), "") << "the whole upload";

    // Three frames of changes: scattered entries of every level, a level's last row and first
    // column (a window's step, as the toroidal table sees it), and entries going to 0.
    for (int frame = 0; frame < 3; ++frame) {
        std::vector<gl::PageTable::Change> changes;
        const std::vector<uint32_t> last = table;
        const auto change = [&](size_t index, uint32_t entry) { table[index] = entry; };
        for (size_t i = size_t(frame) * 37; i < table.size(); i += 97) change(i, uint32_t(i % 4000 + 1));
        const size_t level = size_t(frame + 1) * kPages * kPages;
        for (int x = 0; x < kPages; ++x) change(level + size_t(kPages - 1) * kPages + size_t(x), 0u);
        for (int y = 0; y < kPages; ++y) change(level + size_t(y) * kPages, uint32_t(frame * 100 + y + 1));
        // Each entry that differs, once (as the cache lists them: one writer a texel).
        for (size_t i = 0; i < table.size(); ++i)
            if (table[i] != last[i]) changes.push_back({uint32_t(i), table[i]});
        ASSERT_GT(changes.size(), size_t(kPages));
        before = gl::trafficSoFar();
        (*pageTable)->update(table, kPages, false, changes);
        EXPECT_EQ((gl::trafficSoFar() - before).bytesUploaded, int64_t(changes.size() * 8)) << "frame " << frame;
        EXPECT_EQ((*pageTable)->bytesUploaded(), int64_t(changes.size() * 8)) << "what the frame's figures say";
        EXPECT_EQ((gl::trafficSoFar() - before).dispatches, 1) << "one compute pass";
        EXPECT_EQ((gl::trafficSoFar() - before).workGroups, int64_t(changes.size() + 63) / 64) << "64 changes a group";
        EXPECT_EQ(differences((*pageTable)->read(kLevels), table), "") << "frame " << frame;
    }

    // No change: nothing moves.
    before = gl::trafficSoFar();
    (*pageTable)->update(table, kPages, false, {});
    EXPECT_EQ((gl::trafficSoFar() - before).bytesUploaded, 0);
    EXPECT_EQ((gl::trafficSoFar() - before).dispatches, 0);
    EXPECT_EQ((*pageTable)->bytesUploaded(), 0);

    // Another shape: a new texture, the whole table.
    table = someTable(2 * kPages, 3, 11u);
    before = gl::trafficSoFar();
    (*pageTable)->update(table, 2 * kPages, false, {});
    EXPECT_EQ((gl::trafficSoFar() - before).bytesUploaded, int64_t(table.size() * sizeof(uint32_t)));
    EXPECT_EQ(differences((*pageTable)->read(3), table), "") << "a new shape";
}
