// The build gives Eigen fixed cache sizes (CMakeLists.txt, EIGEN_NO_CPUID and
// EIGEN_DEFAULT_L*_CACHE_SIZE) so that large products block, and so round, the same on every CPU.
#include <gtest/gtest.h>

#include <Eigen/Core>

namespace PKM_TEST_NS {

TEST(EigenBlocking, ProductsBlockWithTheFixedCacheSizesNotTheCpus) {
  EXPECT_EQ(Eigen::l1CacheSize(), 48 * 1024);
  EXPECT_EQ(Eigen::l2CacheSize(), 512 * 1024);
  EXPECT_EQ(Eigen::l3CacheSize(), 16 * 1024 * 1024);
}

}  // namespace PKM_TEST_NS
