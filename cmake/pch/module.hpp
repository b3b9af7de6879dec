// Precompiled for every module library (cmake/PkmPch.cmake): the standard and third-party
// headers most sources include. Only headers whose meaning does not depend on the includer.
#pragma once
#include <fmt/format.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>
