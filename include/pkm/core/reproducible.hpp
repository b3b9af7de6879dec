/// @file
/// @brief Bit-identical results on every machine: what would otherwise follow the CPU is fixed.
#pragma once

#include <cstddef>

namespace pkm {

/// Cache sizes in bytes (L1 data, L2, L3) that pkm gives Eigen's matrix-product blocking. They
/// are those of the machine that wrote the byte-for-byte records in tests/data/golden, so those
/// records hold on every CPU.
inline constexpr std::ptrdiff_t kEigenBlockingL1 = 48 * 1024;
inline constexpr std::ptrdiff_t kEigenBlockingL2 = 512 * 1024;
inline constexpr std::ptrdiff_t kEigenBlockingL3 = 16 * 1024 * 1024;

/// Gives Eigen the fixed cache sizes above (Eigen::setCpuCacheSizes) instead of the ones it reads
/// from the CPU. The sizes choose how Eigen blocks a large matrix product and so the order of its
/// sums: with the CPU's own sizes the last digits of a calibration budget differed between
/// machines whose L1 data caches hold 32 and 48 KiB. Call once at program start, before other
/// threads use Eigen; every front end (pkm, pkm-serve, the Python module) does. Idempotent.
void useReproducibleEigenBlocking();

}  // namespace pkm
