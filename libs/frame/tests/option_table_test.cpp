// The one table of options against what it describes: every member of FrameConfig,
// gl::RenderSettings and the technique's inputs has a row (counted by aggregate initialisation,
// so a field added without one fails here), every row is complete, and every field a check
// reports maps to a flag. No GL.
#include "shadowkit/frame/frame_config.h"
#include "shadowkit/frame/option_table.h"

#include <gtest/gtest.h>

#include <exception>
#include <map>
#include <set>
#include <string>

using namespace shadowkit;

namespace {

// Converts to any member's type: T{AnyMember{}, ...} compiles for as many initialisers as T has
// members, so the count is the aggregate's field count.
struct AnyMember {
    // Only ever named in requires-expressions, never called; defined all the same, since clang
    // takes std::optional's converting constructor for a use (-Wundefined-internal).
    template <class T>
    // NOLINTNEXTLINE(google-explicit-constructor): implicit on purpose
    [[noreturn]] operator T() const {
        std::terminate();
    }
};
template <class T, class... Initialisers>
constexpr size_t memberCount() {
    if constexpr (requires { T{Initialisers{}..., AnyMember{}}; })
        return memberCount<T, Initialisers..., AnyMember>();
    else
        return sizeof...(Initialisers);
}

// The distinct members named in the table directly under `prefix` ("RenderSettings.blur.").
std::set<std::string> membersUnder(const std::string& prefix) {
    std::set<std::string> members;
    for (const frame::OptionRow& row : frame::optionTable()) {
        const std::string member(row.member);
        if (member.compare(0, prefix.size(), prefix) != 0) continue;
        const std::string rest = member.substr(prefix.size());
        members.insert(rest.substr(0, rest.find('.')));
    }
    return members;
}

} // namespace

TEST(OptionTableTest, EveryMemberOfEveryOptionsStructHasARow) {
    const auto expect = [](const std::string& prefix, size_t members) {
        EXPECT_EQ(membersUnder(prefix).size(), members)
            << prefix << ": a member without a row in frame/option_table.cpp (or a row of none)";
    };
    expect("FrameConfig.", memberCount<frame::FrameConfig>());
    expect("FrameConfig.bias.", memberCount<frame::BiasOverrides>());
    expect("FrameConfig.automatic.", memberCount<core::AutoOptions>());
    expect("FrameConfig.heldLattices.", memberCount<core::HysteresisOptions>());
    expect("RenderSettings.", memberCount<gl::RenderSettings>());
    expect("RenderSettings.blur.", memberCount<gl::BlurSettings>());
    expect("RenderSettings.localBias.", memberCount<gl::LocalBiasSettings>());
    expect("ShadowSetupInputs.", memberCount<core::ShadowSetupInputs>());
    expect("ShadowSetupInputs.lispsm.", memberCount<core::LispsmOptions>());
    expect("ShadowSetupInputs.tsm.", memberCount<core::TsmOptions>());
    expect("ShadowSetupInputs.cascades.", memberCount<core::CascadeOptions>());
    expect("ShadowSetupInputs.virtualMaps.", memberCount<core::VirtualOptions>());
}

TEST(OptionTableTest, EveryRowSaysWhatSetsItAndWhereItIsChecked) {
    std::map<std::string, std::string> flagOfField;
    for (const frame::OptionRow& row : frame::optionTable()) {
        const std::string what(row.member);
        // A flag, or where the value comes from; flags are long options.
        EXPECT_TRUE(!row.flag.empty() || !row.source.empty()) << what;
        if (!row.flag.empty()) {
            EXPECT_EQ(row.flag.substr(0, 2), "--") << what;
        }
        // A checked value says its range; a field a check reports names one flag wherever it appears
        // (--size for width and height, --fog for the override and the frame's density).
        if (row.checkedIn == frame::CheckedIn::None) continue;
        EXPECT_FALSE(row.range.empty()) << what;
        if (row.field.empty() || row.flag.empty()) continue;
        const auto [it, first] = flagOfField.emplace(std::string(row.field), std::string(row.flag));
        EXPECT_TRUE(first || it->second == row.flag) << row.field << ": " << it->second << " and " << row.flag;
    }
}

TEST(OptionTableTest, ALibraryErrorNamesItsFlag) {
    // What FrameConfig::check reports for a bad value, mapped back to the flag that set it.
    frame::FrameConfig c;
    c.render.blur.depthThreshold = 0.0f;
    const core::Status s = c.check();
    ASSERT_FALSE(s);
    const frame::OptionRow* row = frame::optionForField(s.errorInfo().field);
    ASSERT_NE(row, nullptr) << s.errorInfo().field;
    EXPECT_EQ(row->flag, "--blur-depth-threshold");
    for (const auto* field : {"lod.pixel_error", "virtual.page_budget", "fog", "spot.cone", "map_size"})
        EXPECT_NE(frame::optionForField(field), nullptr) << field;
    EXPECT_EQ(frame::optionForField("no.such_field"), nullptr);
    EXPECT_EQ(frame::optionForField(""), nullptr);
}
