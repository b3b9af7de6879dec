#include "pkm/core/reproducible.hpp"

#include <Eigen/Core>

namespace pkm {

void useReproducibleEigenBlocking() {
  Eigen::setCpuCacheSizes(kEigenBlockingL1, kEigenBlockingL2, kEigenBlockingL3);
}

}  // namespace pkm
