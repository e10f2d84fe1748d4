#include "core/knn.h"

#include <CGAL/Fuzzy_sphere.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/property_map.h>

#include <boost/iterator/counting_iterator.hpp>

#include "core/cgal_bridge.h"

namespace sharpmesh::detail {
namespace {

using IndexToPoint = IndexedPointMap;

using BaseTraits = CGAL::Search_traits_3<Kernel>;
using Traits = CGAL::Search_traits_adapter<std::uint32_t, IndexToPoint, BaseTraits>;
using Search = CGAL::Orthogonal_k_neighbor_search<Traits>;
using Tree = Search::Tree;
using Splitter = Search::Splitter;
using Distance = Search::Distance;
using Sphere = CGAL::Fuzzy_sphere<Traits>;

}  // namespace

struct KnnIndex::Impl {
  std::vector<Point3> points;
  std::unique_ptr<Tree> tree;
};

KnnIndex::KnnIndex(const std::vector<Vec3>& points) : impl_(std::make_unique<Impl>()) {
  impl_->points = to_cgal(points);
  IndexToPoint map{&impl_->points};
  impl_->tree = std::make_unique<Tree>(boost::counting_iterator<std::uint32_t>(0),
                                       boost::counting_iterator<std::uint32_t>(static_cast<std::uint32_t>(points.size())),
                                       Splitter(), Traits(map));
  impl_->tree->build();
}

KnnIndex::~KnnIndex() = default;

std::size_t KnnIndex::size() const { return impl_->points.size(); }

void KnnIndex::nearest(const Vec3& q, int k, std::vector<std::uint32_t>& indices, std::vector<double>& squared_distances) const {
  indices.clear();
  squared_distances.clear();
  IndexToPoint map{&impl_->points};
  Search search(*impl_->tree, to_cgal(q), static_cast<unsigned>(k), 0, true, Distance(map));
  for (const auto& [index, d2] : search) {
    indices.push_back(index);
    squared_distances.push_back(d2);
  }
}

void KnnIndex::within(const Vec3& q, double radius, std::vector<std::uint32_t>& indices) const {
  indices.clear();
  IndexToPoint map{&impl_->points};
  Sphere sphere(to_cgal(q), radius, 0, Traits(map));
  impl_->tree->search(std::back_inserter(indices), sphere);
}

}  // namespace sharpmesh::detail
