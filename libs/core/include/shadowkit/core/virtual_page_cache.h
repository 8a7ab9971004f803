// The virtual shadow maps' page cache: which pages of the clipmap (virtual_clipmap.h) live in a
// pool of fixed slots, which a frame must draw, and which the lookup reads — pure policy, no GL.
// libs/gl (virtual_pages.h) marks the requests on the GPU, owns the atlas and the page-table
// texture, and draws what this cache schedules.
//
// Pages keep their depth across frames for as long as what they were drawn with (the sun, the
// depth range, the bias, the levels of detail: PageContent) stays the same; then only new and
// invalidated pages are drawn. A slot is reused least recently requested first.
//
// A page budget caps the pages drawn a frame, most needed first: the pages shown, coarsest level
// first (a receiver's fallback before its own page). When the content changes (a moving sun),
// the pages drawn for the old content — the front generation — keep serving while the new one's
// — the back generation — are drawn with what is left of the budget, finest level first; a level
// is shown from the back generation in the frame its last page is drawn, and when every level
// is, the back generation becomes the front one. With a budget that holds every page this is
// the frame an unlimited one draws. At most two generations live in the pool; each level is
// shown from one of them, so a lookup never mixes two suns' depths within a level.
//
// Based on: the page caching of Unreal Engine 5's virtual shadow maps as its "Virtual Shadow
// Maps" pages document it (cached pages kept while the light is still, invalidated under the
// bounds of moving casters), and Lefohn et al. 2007 (pages requested by visible receivers).
// Deviation: the two generations under a budget are ours, so a budget never shows a level half
// drawn for a new sun.
#pragma once

#include "shadowkit/core/aabb.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/core/small_vector.h"
#include "shadowkit/core/virtual_clipmap.h"

#include <cstdint>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

namespace shadowkit::core {

/// What a page's depth depends on besides its key: a change drops every page (without a budget)
/// or starts a new generation (with one).
struct PageContent {
    Mat4 lightFromWorldRotation{1.0};                    ///< the clipmap's light orientation
    Vec3 wsGridOrigin{0.0};                              ///< the page grid's origin
    double zNear = 0.0;                                  ///< the clipmap's light-space depth range, nearest
    double zFar = 0.0;                                   ///< and farthest
    int pageTexels = 0;                                  ///< texels per side of a page
    int guardTexels = 0;                                 ///< texels of guard band drawn around it
    float slopeBias = 0.0f;                              ///< the depth pass's slope bias
    float constantBias = 0.0f;                           ///< and its constant bias
    int cull = 0;                                        ///< caster culling (CasterCull as a number)
    bool lod = false;                                    ///< levels of detail on
    double lodTexelError = 0.0;                          ///< their bound, texels
    double lodFoliageScale = 1.0;                        ///< the bound's multiple for levels that keep coverage
    double lodFade = 0.0;                                ///< the band over which instances cross into those levels
    bool foliageOpacity = false;                         ///< alpha-tested casters in opacity layers, not in depth
    bool operator==(const PageContent&) const = default; ///< the same content
};
/// The content `clipmap`'s pages have with everything else default (tests, engines without bias).
PageContent pageContentOf(const VirtualClipmap& clipmap, int guardTexels);

/// A frame's figures (gl's VirtualPageStats adds the pool's bytes and the triangles drawn).
struct PageCacheStats {
    int pagesRequested = 0; ///< marked by the visible receivers (each with its coarser fallback)
    int pagesResident = 0;  ///< valid in the pool after rendered()
    int pagesRendered = 0;  ///< to draw this frame: newly allocated or invalidated
    int pagesFellBack = 0;  ///< requested but not allocated (pool full): served by a coarser level
    int pagesDeferred = 0;  ///< requested, not drawn: over the page budget (served coarser)
    int levelsBehind = 0;   ///< levels still shown from the older generation
    int lagFrames = 0;      ///< how many frames ago the oldest generation shown was current
    int poolPages = 0;      ///< slots in the pool
    int marksAge = 0;       ///< frames since the requests read were marked (0: this frame's); −1: none
};

/// The pool's slots, the pages they hold and the frame's schedule (see the file's comment).
class VirtualPageCache {
public:
    using ViewList = SmallVector<ShadowView, kMaxShadowViews>; ///< one view per level

    /// `slots` ≥ 1 pages in the pool, each drawn with `guardTexels` around it. A change drops
    /// every page.
    void configure(int slots, int guardTexels);
    int slotCount() const { return static_cast<int>(m_slots.size()); } ///< slots in the pool

    /// The windows whose pages the receivers mark this frame: one view per level of the set-up
    /// as it stands (each level from the generation it is shown from), and while a back
    /// generation is being drawn, the back generation's windows too.
    struct Windows {
        ViewList standing;        ///< every level as it stands
        ViewList back;            ///< the back generation's windows (when drawingBack)
        bool drawingBack = false; ///< a back generation's pages are being drawn
    };
    /// A frame begins: the generations for this frame's `content` (`pageBudget` 0: every page,
    /// a change drops everything at once), and the windows to mark around `wsEye`. `setup` is a
    /// virtual set-up (ShadowSetup::clipmap), in the same coordinates as `wsEye`.
    const Windows& beginFrame(const ShadowSetup& setup, const PageContent& content, int pageBudget, const Vec3& wsEye);
    /// The receivers' requests for the windows beginFrame() gave: one bit per page, level after
    /// level, pagesPerSide² bits each, row-major from the window's first page (`backBits` empty
    /// unless drawingBack). Invalidates the pages under `moved` boxes (old and new places of
    /// moved casters, same coordinates), allocates and schedules at most the budget, and decides
    /// what the lookup reads.
    ///
    /// `markedIn`: the frame whose windows the bits were marked in — this one (0, or frame()),
    /// or an earlier one for which marksApply() holds: requests read late, as a GPU returns them
    /// without a wait; −1: no marks arrived, nothing is requested and the frame shows what is
    /// resident (as it does for marks that do not apply). A page is a place in the clipmap's
    /// grid, so an earlier window's bits name the same pages wherever the window has moved since
    /// (those it has left are not requested); pages this frame's receivers need and no earlier
    /// frame asked for are served by a coarser level until their marks arrive.
    void request(std::span<const uint32_t> standingBits, std::span<const uint32_t> backBits,
                 std::span<const Aabb> moved, int64_t markedIn = 0);
    /// This frame's number (from 1, one per beginFrame()): what bits marked now are tagged with.
    int64_t frame() const { return m_frame; }
    /// Whether bits marked in frame `marked` (one of the last kMarkedFramesKept, this one
    /// included) can be read now: every level of this frame marked then, for the generation it
    /// stands in now, and the same back generation — no change of content, no level switched
    /// and none added since. Otherwise their pages belong to depths no longer drawn, or a level
    /// has none, and the frame needs its own marks.
    bool marksApply(int64_t marked) const;
    static constexpr int kMarkedFramesKept = 8; ///< frames whose windows marksApply() still knows

    /// A page this frame draws, into its slot.
    struct PageToRender {
        PageKey key;             ///< the page
        int slot = 0;            ///< the slot it is drawn into
        Mat4 clipFromWorld{1.0}; ///< the page and its guard band (clipmapPageClipFromWorld)
    };
    std::span<const PageToRender> pagesToRender() const { return m_toRender; } ///< after request()
    /// The set-up the lookup reads this frame: the frame's own, or with the levels still shown
    /// from the previous content's pages placed around this frame's eye.
    const ShadowSetup& shown() const { return m_shown; }
    /// After the pages were drawn: they are valid, and the page table of shown()'s windows is
    /// built: per page, slot + 1 of its valid page of the generation its level is shown from,
    /// else 0; level after level, pagesPerSide² entries each, row-major, each page at its cell
    /// (pageTableCellOf: toroidal, so a moving window changes only the entries it uncovers).
    void rendered();
    std::span<const uint32_t> pageTable() const { return m_table; } ///< after rendered()
    /// An entry of pageTable() that differs from the table the previous rendered() built.
    struct TableChange {
        uint32_t index = 0; ///< into pageTable(): level · pagesPerSide² + row · pagesPerSide + column
        uint32_t entry = 0; ///< its value now
    };
    /// After rendered(): what a copy of the table kept on a GPU must take again — none on a still
    /// camera and sun; a moving eye's uncovered rows and columns and the pages newly resident or
    /// evicted. Empty when tableRebuilt().
    std::span<const TableChange> tableChanges() const { return m_tableChanges; }
    /// Whether the whole table is new: the first, or a new shape (levels, pages a side).
    bool tableRebuilt() const { return m_tableRebuilt; }

    /// Every page dropped: what they hold is no longer known.
    void dropAll();
    const PageCacheStats& stats() const { return m_stats; } ///< of the last frame

private:
    // Pages drawn for one PageContent: a sun, a depth range, a bias.
    struct Generation {
        int64_t id = -1;
        PageContent content;
        int64_t lastCurrent = 0; // the last frame whose content this was
    };
    // A page of a generation: what a slot holds.
    struct SlotKey {
        PageKey page;
        int64_t generation = -1;
        bool operator==(const SlotKey&) const = default;
    };
    struct Slot {
        SlotKey key;
        int64_t lastRequested = -1; // frame index
        bool used = false, valid = false;
    };
    struct KeyHash {
        size_t operator()(const SlotKey& k) const {
            return std::hash<int64_t>()(k.page.x * 73856093 ^ k.page.y * 19349663 ^
                                        int64_t(k.page.exponent) * 83492791 ^ k.generation * 2654435761);
        }
    };
    enum class Outcome { Valid, Drawn, NoSlot, OverBudget };

    // Front and back generations for this frame's content; slots of any other are freed.
    void advanceGenerations(const PageContent& content, int pageBudget);
    // The frame's clipmap with the sun, grid and depth range pages of `generation` were drawn in.
    VirtualClipmap clipmapOf(const Generation& generation) const;
    // Level `level` as `generation` draws it around this frame's eye: the set-up's own view when
    // the generation is the current content's.
    ShadowView levelView(int level, const Generation& generation) const;
    // Whether level `level` is shown from the back generation since an earlier frame.
    bool switched(int level) const;
    // Marks invalid every valid page a moved box (old or new place) touches, in any level.
    void invalidateUnder(std::span<const Aabb> moved);
    // Appends the keys of the bits set for level `level` of `window` (the window they were
    // marked in), as pages of `generation`, those inside `shown` (this frame's window of the
    // same level) only: a page marked in a window that has moved on since cannot be shown.
    void appendKeys(const ShadowView& window, int level, std::span<const uint32_t> bits, int64_t generation,
                    const ShadowView& shown, std::vector<SlotKey>& keys) const;
    // Marks every resident page requested this frame, and lists the slots that may be taken,
    // free ones first, then the least recently requested.
    using LevelKeys = std::vector<std::vector<SlotKey>>; // per level
    void touch(const LevelKeys& standing, const LevelKeys& back);
    // Schedules one requested page: valid already, drawn (allocating a slot), or not.
    Outcome schedule(const SlotKey& key);
    // Counts a level's requests into the frame's figures as it schedules them.
    void scheduleShown(const std::vector<SlotKey>& keys);
    // Step 6: each level from the back generation if it switched, else from the front.
    void decideShown(const std::vector<bool>& switchNow);

    int m_guardTexels = 0;
    std::vector<Slot> m_slots;
    std::unordered_map<SlotKey, int, KeyHash> m_resident;
    Generation m_front;               // the pages on screen (every level not yet shown from m_back)
    std::optional<Generation> m_back; // page budget: a newer content's pages, being drawn
    std::vector<int> m_backExponents; // levels (by exponent) shown from m_back
    int64_t m_nextGeneration = 0;
    int64_t m_frame = 0;

    // What a frame's marks refer to: its windows and the generation of each, kept a few frames
    // for marks read late (marksApply).
    struct MarkedFrame {
        int64_t frame = 0;
        Windows windows;
        int pagesPerSide = 0;
        SmallVector<int64_t, kMaxShadowViews> standingGeneration; // per level
        int64_t backGeneration = -1;                              // -1: none
        int levelWith(int exponent) const;                        // the index of the level, −1: none
        // Whether these marks name pages of the generations `now` draws, for each of its levels.
        bool serves(const MarkedFrame& now) const;
    };
    const MarkedFrame* markedFrame(int64_t frame) const;
    std::vector<MarkedFrame> m_marked; // the last kMarkedFramesKept frames', oldest first

    // The frame in flight (beginFrame to rendered).
    ShadowSetup m_setup;
    PageContent m_content;
    Vec3 m_wsEye{0.0};
    Windows m_windows;
    int m_budgetLeft = 0;
    std::vector<int> m_spare;
    size_t m_nextSpare = 0;
    std::vector<PageToRender> m_toRender;
    ShadowSetup m_shown;
    std::vector<int64_t> m_shownGeneration; // per level of m_shown
    std::vector<uint32_t> m_table, m_previousTable;
    std::vector<TableChange> m_tableChanges; // m_table against m_previousTable
    bool m_tableRebuilt = true;
    int m_tablePagesPerSide = 0; // m_table's
    PageCacheStats m_stats;
};

} // namespace shadowkit::core
