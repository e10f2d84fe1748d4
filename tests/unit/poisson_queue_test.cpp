// The Poisson refinement's queue (src/implicit/poisson_refinement_order.h):
// cells of equal quality leave in the order they were queued, whatever
// their addresses. CGAL's own Double_map pops them in address order (here 1
// of 167 in queued order), which made the Poisson function, and the mesh,
// change between identical runs.
#include <gtest/gtest.h>

#include "implicit/poisson_refinement_order.h"

#include <CGAL/Poisson_reconstruction_function.h>

#include <algorithm>
#include <random>
#include <vector>

namespace sharpmesh {
namespace {

using detail::PoissonCell;
using detail::PoissonTriangulation;

std::vector<PoissonCell> cells_by_decreasing_address(PoissonTriangulation& tr) {
  std::mt19937 generator(3);
  std::uniform_real_distribution<double> coordinate(0, 1);
  for (int i = 0; i < 40; ++i)
    tr.insert(PoissonTriangulation::Point(coordinate(generator), coordinate(generator), coordinate(generator)),
              PoissonTriangulation::INPUT, PoissonCell(), CGAL::Poisson_visitor());
  std::vector<PoissonCell> cells;
  for (auto c = tr.finite_cells_begin(); c != tr.finite_cells_end(); ++c) cells.push_back(c);
  std::sort(cells.begin(), cells.end(), [](PoissonCell a, PoissonCell b) { return &*a > &*b; });
  return cells;
}

TEST(PoissonRefinementQueue, EqualQualitiesLeaveInQueuedOrderNotAddressOrder) {
  PoissonTriangulation tr;
  const std::vector<PoissonCell> cells = cells_by_decreasing_address(tr);
  ASSERT_GT(cells.size(), 50u);
  CGAL::Double_map<PoissonCell, double> queue;
  for (PoissonCell c : cells) EXPECT_TRUE(queue.insert(c, 1.0));
  std::size_t k = 0;
  while (!queue.empty()) {
    ASSERT_LT(k, cells.size());
    EXPECT_EQ(queue.front()->second, cells[k++]);
    queue.pop_front();
  }
  EXPECT_EQ(k, cells.size());
}

TEST(PoissonRefinementQueue, OrdersByQualityRefusesDuplicatesAndErases) {
  PoissonTriangulation tr;
  const std::vector<PoissonCell> cells = cells_by_decreasing_address(tr);
  CGAL::Double_map<PoissonCell, double> queue;
  EXPECT_TRUE(queue.insert(cells[0], 3.0));
  EXPECT_TRUE(queue.insert(cells[1], 1.0));
  EXPECT_TRUE(queue.insert(cells[2], 2.0));
  EXPECT_FALSE(queue.insert(cells[1], 0.5));  // queued already: unchanged
  EXPECT_EQ(queue.size(), 3u);
  queue.erase(cells[2]);
  queue.erase(cells[3]);  // not queued: nothing happens
  EXPECT_EQ(queue.size(), 2u);
  EXPECT_EQ(queue.front()->second, cells[1]);
  EXPECT_EQ(queue.front()->first, 1.0);
  queue.pop_front();
  EXPECT_EQ(queue.front()->second, cells[0]);
  queue.pop_front();
  EXPECT_TRUE(queue.empty());
  EXPECT_TRUE(queue.insert(cells[1], 1.0));  // popped cells can be queued again
}

}  // namespace
}  // namespace sharpmesh
