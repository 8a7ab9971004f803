// KHR_debug output: one line per driver message on stderr, duplicates suppressed.
#pragma once

namespace shadowkit::gl {
void installDebugOutput();
}
