// Virtual shadow maps' page table, updated in place (virtual_pages.h): the entries the page cache
// found changed since the last frame (core::VirtualPageCache::tableChanges), each written into
// its texel. The table is addressed toroidally (core::pageTableCellOf), so a moving window
// changes only the entries where a page came or went, not its level: a frame uploads eight bytes
// an entry changed instead of the whole table.
layout(local_size_x = 64) in;

layout(r32ui, binding = SK_PAGE_TABLE_IMAGE_UNIT) uniform writeonly uimage2D pageTable;
// x: level · n² + row · n + column; y: the entry (slot + 1, 0: none).
layout(std430, binding = SK_PAGE_TABLE_CHANGES_BINDING) readonly buffer Changes { uvec2 changes[]; };
layout(location = 0) uniform uint changeCount;
layout(location = 1) uniform uint pagesPerSide; // n: level l's rows are l · n … l · n + n − 1

void main() {
    const uint i = gl_GlobalInvocationID.x;
    if (i >= changeCount) return;
    const uvec2 change = changes[i];
    imageStore(pageTable, ivec2(change.x % pagesPerSide, change.x / pagesPerSide), uvec4(change.y));
}
