// The page bookkeeping of a virtual shadow map (techniques/adaptive.cpp), kept apart from GL so it
// can be tested on its own.
//
// The virtual map is a mip chain: level l has (virtualSize >> l)^2 texels in pages of pageSize^2,
// so (virtualSize / pageSize >> l)^2 pages; the coarsest level is one page covering the whole map.
// Every level's page cells are stacked in one table (level 0's rows first, then level 1's, ...),
// pagesPerSide(0) wide: the request image that the mark pass counts pixels into, and the page
// table that the visibility pass reads (a pool slot, or -1), share that layout.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace so {

struct VirtualMapLayout {
    int virtualSize = 0, pageSize = 0;

    int levels() const;  // log2(virtualSize / pageSize) + 1
    int pagesPerSide(int level) const { return (virtualSize / pageSize) >> level; }
    int tableWidth() const { return pagesPerSide(0); }
    int tableHeight() const { return tableRow(levels()); }
    // The first table row of `level`'s cells (level == levels(): the table's height).
    int tableRow(int level) const;
    size_t cell(int level, int x, int y) const {
        return size_t(tableRow(level) + y) * size_t(tableWidth()) + size_t(x);
    }
};

// A page to render: its level, its cell in that level, and its slot in the physical pool.
struct PageSlot {
    int level, x, y, slot;
};

// One frame's allocation.
struct PageAllocation {
    std::vector<int32_t> table;   // the page table: per cell its pool slot, or -1
    std::vector<PageSlot> pages;  // the pages to render, each after its parent
    int64_t marked = 0;           // pages some pixel asked for directly
    int64_t requested = 0;  // those and their ancestors (the fallbacks), the coarsest page always
    int64_t dropped = 0;    // requested, but the pool was full
    int finestLevel = 0;    // the finest level with a page in the pool
    int levelsMarked = 0;   // how many levels some pixel asked for
};

// Allocates pool slots to the requested pages. `pixels` holds per table cell the number of camera
// pixels that asked for that page (the mark pass's counts). Every page a pixel asks for brings its
// ancestors, which serve as its fallback. Slots are given greedily, a page always after its parent
// (the coarsest page first, always resident), to the page whose pixels are served the most levels
// coarser than the finest of them needs (then to the one with most pixels), until the pool's
// `poolPages` are used up: a full pool evens out the predicted aliasing over the image, instead of
// perfecting some pixels while others stay coarse, and a dropped page's pixels always find a
// resident ancestor.
// `resident`: an earlier round's allocation, whose pages keep their slots (and count as requested
// and rendered); the new pages take the slots after them.
PageAllocation allocatePages(const VirtualMapLayout& layout, const std::vector<uint32_t>& pixels,
                             int poolPages, const PageAllocation* resident = nullptr);

}  // namespace so
