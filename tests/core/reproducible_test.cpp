#include "pkm/core/reproducible.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>

namespace pkm {
namespace {

TEST(Reproducible, EigenBlocksProductsWithTheFixedCacheSizes) {
  useReproducibleEigenBlocking();
  EXPECT_EQ(Eigen::l1CacheSize(), kEigenBlockingL1);
  EXPECT_EQ(Eigen::l2CacheSize(), kEigenBlockingL2);
  EXPECT_EQ(Eigen::l3CacheSize(), kEigenBlockingL3);
  useReproducibleEigenBlocking();  // idempotent
  EXPECT_EQ(Eigen::l1CacheSize(), kEigenBlockingL1);
}

}  // namespace
}  // namespace pkm
