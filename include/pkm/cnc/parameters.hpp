/// @file
/// @brief RS274NGC parameter store as LinuxCNC 2.9 lays it out ("Numbered Parameters", "Named
/// Parameters"): #1..#5601 numbered parameters with #1-#30 local to a subroutine call, the
/// coordinate-system block (#5211-#5219 G92, #5220 active system, #5221-#5230 G54 ... #5381-#5390
/// G59.3, X Y Z A B C U V W R each), named parameters local to a call (`#<name>`) or global
/// (`#<_name>`).
#pragma once

#include <array>
#include <string>
#include <unordered_map>
#include <vector>

namespace pkm::cnc {

/// Numbered parameters: LinuxCNC's RS274NGC_MAX_PARAMETERS.
inline constexpr int kParameterCount = 5602;
/// #5211: first G92 offset parameter (X); #5210 says whether G92 offsets are applied.
inline constexpr int kG92Base = 5211;
/// First of the G28 (#5161-#5166) and G30 (#5181-#5186) stored positions, X Y Z A B C in machine
/// coordinates (mm, degrees).
inline constexpr int kG28Base = 5161;
inline constexpr int kG30Base = 5181;
/// #5220: the active coordinate system, 1 (G54) .. 9 (G59.3).
inline constexpr int kActiveSystemParam = 5220;
/// First parameter (X) of coordinate system `n` (1 = G54 .. 9 = G59.3): 5201 + 20 n.
[[nodiscard]] constexpr int coordinateSystemBase(int n) { return 5201 + 20 * n; }
/// The rotation (R, degrees about Z) of a coordinate system: coordinateSystemBase(n) + 9.
inline constexpr int kRotationIndex = 9;
/// True when parameter `index` holds a length (stored in mm, read and written in program units).
[[nodiscard]] bool isLengthParameter(int index);

/// Numbered and named parameter values with subroutine scopes.
class Parameters {
 public:
  Parameters();
  /// Stored value of `#index` (1 <= index < kParameterCount; lengths in mm).
  [[nodiscard]] double get(int index) const { return numbered_[static_cast<std::size_t>(index)]; }
  /// Stores `#index`.
  void set(int index, double value) { numbered_[static_cast<std::size_t>(index)] = value; }
  /// True when `#<name>` exists in the current scope (global names start with '_').
  [[nodiscard]] bool exists(const std::string& name) const;
  /// Value of `#<name>`; throws GcodeError when it is not defined.
  [[nodiscard]] double named(const std::string& name) const;
  /// Sets `#<name>` in the current scope (or globally for names starting with '_').
  void setNamed(const std::string& name, double value);
  /// Enters a subroutine: saves #1-#30, sets them to `args` (the rest 0), opens a local scope.
  void pushCall(const std::vector<double>& args);
  /// Leaves a subroutine: restores #1-#30 and drops its local names.
  void popCall();
  /// Number of open subroutine calls.
  [[nodiscard]] std::size_t callDepth() const { return saved_.size(); }

 private:
  std::vector<double> numbered_;
  std::unordered_map<std::string, double> globals_;
  std::vector<std::unordered_map<std::string, double>> locals_;  // [0] = main program
  std::vector<std::array<double, 30>> saved_;
};

}  // namespace pkm::cnc
