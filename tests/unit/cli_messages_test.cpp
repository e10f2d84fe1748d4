// The command line's filter of CGAL's protection warning
// (apps/sharpmesh/cgal_messages.h): exactly those two lines are dropped.
#include <gtest/gtest.h>

#include <iostream>
#include <sstream>

#include "apps/sharpmesh/cgal_messages.h"

TEST(CgalMessageFilter, DropsTheProtectionWarningAndPassesEverythingElse) {
  std::ostringstream seen;
  std::streambuf* const original = std::cerr.rdbuf(seen.rdbuf());
  {
    const sharpmesh::cli::CgalMessageFilter filter;
    std::cerr << "before\n";
    // As Protect_edges_sizing_field writes it: pieces, with std::cerr
    // flushing after each.
    std::cerr << "Warning : features protection has reached maximal " << " number of loops." << std::endl
              << "          It might result in a crash." << std::endl;
    std::cerr << "It might result in a crash, said someone else\n";
    std::cerr << "unfinished";
  }
  std::cerr.rdbuf(original);
  EXPECT_EQ(seen.str(), "before\nIt might result in a crash, said someone else\nunfinished");
}
