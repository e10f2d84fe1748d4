// A deterministic queue for the Delaunay refinement inside CGAL's Poisson
// reconstruction. Include before <CGAL/Poisson_reconstruction_function.h>.
//
// CGAL 5.5 queues the bad cells of that refinement in a CGAL::Double_map
// built on a boost bimap: a set keyed by Cell_handle (the cell's address,
// since these cells carry no time stamp) and a multiset keyed by quality.
// Each insertion is hinted by the address-ordered set, and the multiset
// takes that hint too, so cells of exactly equal quality (couplingdown 50k:
// a first tie at step 1,230 of the first pass) leave in an order set by
// where the allocator put them. The Poisson function then changed between identical
// runs (couplingdown 50k after feature extraction: one run in four, the
// function's sum over the samples 4e-6 apart, 2 facets more in the mesh);
// CGAL issue #6240 reports it. This partial specialization, for the Poisson
// triangulation's cells only, keeps CGAL's interface with std containers:
// equal qualities leave in insertion order, which depends on the data only.
#pragma once

#include <CGAL/Double_map.h>
#include <CGAL/Reconstruction_triangulation_3.h>
#include <CGAL/Robust_weighted_circumcenter_filtered_traits_3.h>

#include <functional>
#include <map>

#include "core/cgal_bridge.h"

namespace sharpmesh::detail {
// As Poisson_reconstruction_function<Kernel>::Triangulation.
using PoissonTriangulation = CGAL::Reconstruction_triangulation_3<CGAL::Robust_circumcenter_filtered_traits_3<Kernel>>;
using PoissonCell = PoissonTriangulation::Cell_handle;
}  // namespace sharpmesh::detail

namespace CGAL {

template <class Data>
class Double_map<sharpmesh::detail::PoissonCell, Data, std::less<sharpmesh::detail::PoissonCell>, std::less<Data>> {
 public:
  using Key = sharpmesh::detail::PoissonCell;
  using Reverse_func = std::multimap<Data, Key>;  // insert() goes after equal keys
  using reverse_iterator = typename Reverse_func::iterator;
  using size_type = typename Reverse_func::size_type;

  bool empty() const { return by_quality_.empty(); }
  size_type size() const { return by_quality_.size(); }
  void clear() {
    by_quality_.clear();
    by_cell_.clear();
  }
  /// False (and no change) when the cell is queued already.
  bool insert(const Key& k, const Data& d) {
    auto [at, inserted] = by_cell_.try_emplace(k);
    if (!inserted) return false;
    at->second = by_quality_.insert({d, k});
    return true;
  }
  reverse_iterator front() { return by_quality_.begin(); }
  void pop_front() {
    by_cell_.erase(by_quality_.begin()->second);
    by_quality_.erase(by_quality_.begin());
  }
  void erase(const Key& k) {
    auto at = by_cell_.find(k);
    if (at == by_cell_.end()) return;
    by_quality_.erase(at->second);
    by_cell_.erase(at);
  }

 private:
  Reverse_func by_quality_;
  std::map<Key, reverse_iterator> by_cell_;  // lookup only; its order is never used
};

}  // namespace CGAL
