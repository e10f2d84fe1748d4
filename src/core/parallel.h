// The library's one parallel loop. Every parallel pass goes through here, so
// the thread limit (the options' `threads`, applied by run_with_threads) and
// progress reporting are decided in one place; the build refuses a raw
// tbb::parallel_for elsewhere (cmake/check_layers.cmake).
#pragma once

#include <sharpmesh/progress.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstddef>
#include <string>
#include <utility>

namespace sharpmesh::detail {

/// Runs body(begin, end) on disjoint chunks covering [0, n), in parallel;
/// a chunk holds at least `grain` indices (TBB's auto partitioner splits
/// further only while threads are idle). Scratch buffers declared in the
/// body live once per chunk, not once per index.
template <class Body>
void parallel_chunks(std::size_t n, std::size_t grain, const Body& body) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, std::max<std::size_t>(grain, 1)),
                    [&](const tbb::blocked_range<std::size_t>& range) { body(range.begin(), range.end()); });
}

/// As above, reporting `stage` to `progress` every `block` indices. The
/// reports come from the calling thread between blocks, because a Progress
/// callback (a Python function, a terminal line) need not be thread safe.
template <class Body>
void parallel_chunks(std::size_t n, std::size_t grain, const Body& body, const Progress& progress, const std::string& stage,
                     std::size_t block) {
  block = std::max<std::size_t>(block, 1);
  for (std::size_t first = 0; first < n; first += block) {
    report_progress(progress, stage, static_cast<double>(first) / static_cast<double>(n));
    const std::size_t last = std::min(n, first + block);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(first, last, std::max<std::size_t>(grain, 1)),
                      [&](const tbb::blocked_range<std::size_t>& range) { body(range.begin(), range.end()); });
  }
  report_progress(progress, stage, 1.0);
}

/// Runs body(i) for every i in [0, n), in parallel.
template <class Body>
void parallel_for(std::size_t n, const Body& body) {
  parallel_chunks(n, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i != end; ++i) body(i);
  });
}

/// Runs `work` with at most `threads` worker threads for the parallel loops
/// inside it (0: every core). A task arena limits only this call, not the
/// process, so a library caller's other threads keep their own limits.
template <class Work>
decltype(auto) run_with_threads(int threads, Work&& work) {
  if (threads <= 0) return std::forward<Work>(work)();
  tbb::task_arena arena(threads);
  return arena.execute(std::forward<Work>(work));
}

}  // namespace sharpmesh::detail
