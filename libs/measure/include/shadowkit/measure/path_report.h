// The report of a measured camera path (`shadowkit eval --path`, Python, sweeps): one row per
// frame — its figures against the truth, its flicker against the previous frame, what the frame
// driver decided (refits, auto's choice), its virtual pages and soft figures — and the summary
// over the path, as the CSV and JSON files give them. The still view's report is
// eval::writeJsonReport's; this is the sequence's, beside it.
#pragma once

#include "shadowkit/eval/metrics.h"
#include "shadowkit/eval/soft_truth.h"
#include "shadowkit/eval/temporal.h"
#include "shadowkit/gl/frame_stats.h"
#include "shadowkit/measure/path_measurer.h"

#include <nlohmann/json_fwd.hpp>

#include <optional>
#include <string>
#include <vector>

namespace shadowkit::measure {

struct PathRow {
    int frame = 0;
    double time = 0.0; // seconds along the path
    eval::Figures figures;
    std::optional<eval::TemporalFigures> temporal;    // none for the first frame
    std::optional<int> refittedViews;                 // --stabilize with held lattices: maps refitted (pops)
    std::optional<std::string> autoChoice;            // --technique auto: what it chose (core::describe)
    double autoMilliseconds = 0.0;                    // and the CPU time of the choice (model + search)
    std::optional<gl::VirtualPageStats> virtualPages; // --technique virtual: the frame's pages
    size_t shadowTriangles = 0;                       // drawn by the frame's sun shadow pass
    std::optional<eval::SoftFigures> soft;            // --sun-angle: against the sun disk's soft truth
    double seconds = 0.0;                             // wall-clock of the frame, measurement included
};

// A sequence of measured frames and what the driver did along it.
class PathReport {
public:
    PathReport(std::string path, bool heldLattices, bool automatic)
        : m_path(std::move(path)), m_held(heldLattices), m_automatic(automatic) {}

    // Frame `number` at `time`, measured (PathMeasurer::next) in `seconds`; returns its row.
    const PathRow& add(int number, double time, const PathFrame& measured, double seconds);
    const std::vector<PathRow>& rows() const { return m_rows; }

    // Mean, 95th percentile (nearest rank) and maximum of a figure over the frames that have it.
    struct Summary {
        double mean = 0.0, p95 = 0.0, max = 0.0;
    };
    static Summary summarise(std::vector<double> values);

    std::string technique() const; // "auto" with auto, else the frames' technique
    Summary flicker() const;       // flicker_pct, frames after the first
    Summary truthChange() const;   // truth_change_pct
    // level_pop_pct (eval::LevelPops::popPct), frames after the first, when measured; none else.
    std::optional<Summary> levelPops() const;
    Summary wrong() const;            // wrong_pct, every frame
    Summary autoMilliseconds() const; // the choice's CPU time, frames after the first (which searches in full)
    // --technique auto: frames whose family (technique, maps, per-split warp) differs from the last's.
    int familySwitches() const;
    // --stabilize with held lattices: frames with a refit, and views refitted to cover the view / grown stale.
    int refitFrames() const { return m_refitFrames; }
    int refitsToCover() const { return m_toCover; }
    int refitsStale() const { return m_stale; }

    // The lines `eval --path` prints under its table: auto's and the refits' when they apply,
    // the summary, and the soft figures' when the sun had a size.
    std::string summaryText() const;
    // One line per frame, header first (eval --path --csv).
    std::string csv() const;
    // {"path", "technique", "refits", "summary", "frames", ["sun_angle_deg"], ["auto"]} (eval --path --json);
    // with pops measured, "level_pop_pct" in the summary and each frame's "level_pops".
    nlohmann::json json() const;

private:
    std::vector<double> softValues(double eval::SoftFigures::*field) const;

    std::string m_path;
    bool m_held = false, m_automatic = false;
    std::string m_technique;
    std::vector<PathRow> m_rows;
    std::vector<core::ShadowSetupInputs> m_autoChosen;
    int m_refitFrames = 0, m_toCover = 0, m_stale = 0;
};

} // namespace shadowkit::measure
