#include "shadowkit/gl/read_backs.h"

#include <atomic>

namespace shadowkit::gl {
namespace {
std::atomic<int64_t> g_readBacks{0}; // renderers may live on several threads, each with its context
std::atomic<int64_t> g_bytesUploaded{0}, g_bytesReadBack{0};
std::atomic<int64_t> g_dispatches{0}, g_workGroups{0};
} // namespace

int64_t readBacksMade() { return g_readBacks.load(std::memory_order_relaxed); }

void detail::countReadBack() { g_readBacks.fetch_add(1, std::memory_order_relaxed); }

int64_t bytesUploaded() { return g_bytesUploaded.load(std::memory_order_relaxed); }
int64_t bytesReadBack() { return g_bytesReadBack.load(std::memory_order_relaxed); }

void detail::countUpload(int64_t bytes) { g_bytesUploaded.fetch_add(bytes, std::memory_order_relaxed); }
void detail::countBytesReadBack(int64_t bytes) { g_bytesReadBack.fetch_add(bytes, std::memory_order_relaxed); }

int64_t dispatchesMade() { return g_dispatches.load(std::memory_order_relaxed); }
int64_t workGroupsDispatched() { return g_workGroups.load(std::memory_order_relaxed); }

void detail::countDispatch(int64_t workGroups) {
    g_dispatches.fetch_add(1, std::memory_order_relaxed);
    g_workGroups.fetch_add(workGroups, std::memory_order_relaxed);
}

} // namespace shadowkit::gl
