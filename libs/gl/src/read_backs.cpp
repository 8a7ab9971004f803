#include "shadowkit/gl/read_backs.h"

#include <atomic>

namespace shadowkit::gl {
namespace {
std::atomic<int64_t> g_readBacks{0}; // renderers may live on several threads, each with its context
} // namespace

int64_t readBacksMade() { return g_readBacks.load(std::memory_order_relaxed); }

void detail::countReadBack() { g_readBacks.fetch_add(1, std::memory_order_relaxed); }

} // namespace shadowkit::gl
