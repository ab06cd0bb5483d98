#include "raster_compare/gl/shadow_maps/virtual_shadow_map.h"

#include <algorithm>
#include <bit>
#include <functional>
#include <queue>
#include <tuple>

#include "core/error.h"

namespace so {

int VirtualMapLayout::levels() const {
    return std::countr_zero(unsigned(virtualSize / pageSize)) + 1;
}

int VirtualMapLayout::tableRow(int level) const {
    int row = 0;
    for (int l = 0; l < level; ++l) row += pagesPerSide(l);
    return row;
}

namespace {

// What the pixels under a page ask for: how many there are (its own and every finer page's
// below it) and the finest level any of them needs.
struct PageDemand {
    uint64_t pixels = 0;
    int finestNeed = 1 << 20;
};

std::vector<PageDemand> demands(const VirtualMapLayout& layout, const std::vector<uint32_t>& pixels,
                                PageAllocation& a) {
    std::vector<PageDemand> d(pixels.size());
    const int levels = layout.levels();
    for (int l = 0; l < levels; ++l) {
        int64_t marked = 0;
        for (int y = 0; y < layout.pagesPerSide(l); ++y)
            for (int x = 0; x < layout.pagesPerSide(l); ++x) {
                const size_t c = layout.cell(l, x, y);
                if (pixels[c] > 0) {
                    ++marked;
                    d[c].pixels += pixels[c];
                    d[c].finestNeed = std::min(d[c].finestNeed, l);
                }
                if (l + 1 == levels) continue;
                PageDemand& parent = d[layout.cell(l + 1, x / 2, y / 2)];
                parent.pixels += d[c].pixels;
                parent.finestNeed = std::min(parent.finestNeed, d[c].finestNeed);
            }
        a.marked += marked;
        a.levelsMarked += marked > 0;
    }
    return d;
}

// A page that can be allocated next (its parent is resident): the pixels under it are served
// (by the parent) `deficit` levels coarser than the finest of them needs.
struct Candidate {
    int deficit;
    uint64_t pixels;
    int level, x, y;
    // Largest deficit first, then most pixels, then table order (deterministic).
    bool operator<(const Candidate& o) const {
        return std::tie(deficit, pixels, o.level, o.y, o.x) <
               std::tie(o.deficit, o.pixels, level, y, x);
    }
};

}  // namespace

PageAllocation allocatePages(const VirtualMapLayout& layout, const std::vector<uint32_t>& pixels,
                             int poolPages, const PageAllocation* resident) {
    const size_t cells = size_t(layout.tableWidth()) * size_t(layout.tableHeight());
    SO_CHECK_EQ(pixels.size(), cells);
    SO_CHECK(poolPages >= 1);
    const int top = layout.levels() - 1;
    PageAllocation a;
    a.finestLevel = top;
    const std::vector<PageDemand> d = demands(layout, pixels, a);
    a.table.assign(cells, -1);
    if (resident) {
        SO_CHECK_EQ(resident->table.size(), cells);
        a.table = resident->table;
        a.pages = resident->pages;
        a.finestLevel = resident->finestLevel;
    }
    // A page is wanted where pixels under it ask for it or finer (the coarsest: always).
    auto wanted = [&](int l, size_t c) { return d[c].pixels > 0 || (l == top && !resident); };
    int64_t newlyRequested = 0;
    for (int l = 0; l <= top; ++l)
        for (int y = 0; y < layout.pagesPerSide(l); ++y)
            for (int x = 0; x < layout.pagesPerSide(l); ++x) {
                const size_t c = layout.cell(l, x, y);
                newlyRequested += wanted(l, c) && a.table[c] < 0;
            }
    a.requested = int64_t(a.pages.size()) + newlyRequested;
    // Greedy, a page's parent before it: the candidates are the wanted pages under resident ones.
    std::priority_queue<Candidate> queue;
    std::function<void(int, int, int)> consider = [&](int l, int x, int y) {
        const size_t c = layout.cell(l, x, y);
        if (!wanted(l, c)) return;
        if (a.table[c] < 0) {
            queue.push({l + 1 - std::min(d[c].finestNeed, l), d[c].pixels, l, x, y});
            return;
        }
        for (int k = 0; k < 4 && l > 0; ++k) consider(l - 1, 2 * x + (k & 1), 2 * y + k / 2);
    };
    consider(top, 0, 0);
    int64_t allocated = 0;
    while (!queue.empty() && int(a.pages.size()) < poolPages) {
        const Candidate p = queue.top();
        queue.pop();
        const int slot = int(a.pages.size());
        a.table[layout.cell(p.level, p.x, p.y)] = slot;
        a.pages.push_back({p.level, p.x, p.y, slot});
        a.finestLevel = std::min(a.finestLevel, p.level);
        ++allocated;
        for (int k = 0; k < 4 && p.level > 0; ++k)
            consider(p.level - 1, 2 * p.x + (k & 1), 2 * p.y + k / 2);
    }
    a.dropped = newlyRequested - allocated;
    return a;
}

}  // namespace so
