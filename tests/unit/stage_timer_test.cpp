// Peak memory per stage and of the process (include/sharpmesh/timing.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "sharpmesh/timing.h"

namespace sharpmesh {
namespace {

constexpr std::size_t kMiB = 1024 * 1024;

/// Touches `bytes` of fresh memory, so that they are resident, and frees them.
void touch_and_free(std::size_t bytes) {
  std::vector<char> block(bytes);
  std::memset(block.data(), 1, bytes);
  volatile char sink = block[bytes / 2];
  (void)sink;
}

TEST(StageTimer, AStagePeakCountsWhatItTouchedAndTheProcessPeakIsNeverBelowAnyStage) {
  std::vector<StageTiming> stages;
  // Above the process's mark so far, so that the stage raises it (earlier
  // tests in the same process may have gone higher than 64 MiB).
  const std::size_t before = current_rss_bytes();
  const std::size_t raise = peak_rss_bytes() - std::min(peak_rss_bytes(), before) + 64 * kMiB;
  {
    StageTimer big(stages, "big");
    touch_and_free(raise);
  }
  {
    StageTimer small(stages, "small");
    touch_and_free(8 * kMiB);
  }
  ASSERT_EQ(stages.size(), 2u);
  EXPECT_GE(stages[0].peak_rss_bytes, before + raise - 8 * kMiB);
  // The kernel's mark covers every stage: a later, smaller stage does not
  // lower what `time -v` or a benchmark reads for the process.
  EXPECT_GE(peak_rss_bytes(), stages[0].peak_rss_bytes);
  EXPECT_GE(peak_rss_bytes(), stages[1].peak_rss_bytes);
}

}  // namespace
}  // namespace sharpmesh
