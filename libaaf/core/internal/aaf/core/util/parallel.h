#pragma once

// The one way the libraries run loops in parallel (oneTBB underneath, on the
// current arena). Every helper calls its body once per index or tile, and a
// body's results must depend only on what it is given, never on which
// thread runs it or on what ran before: then nothing depends on the thread
// count or the schedule.
#include <tbb/blocked_range.h>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

namespace aaf {

/// Calls `body(y)` for every row y in [0, height), rows in parallel.
template <typename Body>
void parallel_for_rows(int height, const Body &body) {
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int> &rows) {
        for (int y = rows.begin(); y != rows.end(); ++y) body(y);
    });
}

/// Calls `body(i)` for every i in [0, count), each index its own task:
/// for work items sized for balance already (bands, tiles), which the
/// scheduler is not to group.
template <typename Body>
void parallel_for_each_index(int count, const Body &body) {
    tbb::parallel_for(
        tbb::blocked_range<int>(0, count, 1),
        [&](const tbb::blocked_range<int> &range) {
            for (int i = range.begin(); i != range.end(); ++i) body(i);
        },
        tbb::simple_partitioner());
}

/// A rectangle of rows [row_begin, row_end) by columns [col_begin, col_end).
struct TileRange {
    int row_begin, row_end, col_begin, col_end;
};

/// Calls `body(tile)` over [0, rows) x [0, cols) split into tiles of at most
/// `tile_rows` by `tile_cols` (halving the ranges until they fit), each
/// tile its own task.
template <typename Body>
void parallel_for_tiles(int rows, int tile_rows, int cols, int tile_cols, const Body &body) {
    tbb::parallel_for(
        tbb::blocked_range2d<int>(0, rows, tile_rows, 0, cols, tile_cols),
        [&](const tbb::blocked_range2d<int> &tile) {
            body(TileRange{tile.rows().begin(), tile.rows().end(), tile.cols().begin(), tile.cols().end()});
        },
        tbb::simple_partitioner());
}

}  // namespace aaf
