/// @file
/// @brief SINUMERIK 840D sl interpolatory compensation part programs: measuring-system error
/// compensation (MSEC/EEC, `$AA_ENC_COMP`) and sag/cross compensation (CEC, `$AN_CEC`): writers,
/// strict readers and the controller's use of a table (SINUMERIK 840D sl Function Manual
/// Extended Functions K3, 6FC5397-1BP40-3BA1, §4.4; the sign table of docs/compensation.md).
///
/// Sign (K3): "A positive compensation value causes the corresponding machine axis to move in the
/// negative direction", so the stored value is the error e = actual − commanded (pkm uses the
/// same sign for $AN_CEC; docs/compensation.md, "CEC"). Values and positions in mm; positions
/// below MIN / above MAX use the first / last value; linear interpolation between equidistant
/// points.
#pragma once

#include <string>
#include <vector>

#include "pkm/compensation/axis_table.hpp"

namespace pkm::compensation {

/// One EEC table: `$AA_ENC_COMP[e,N,AXIS]` for N = 0..n−1, `$AA_ENC_COMP_STEP[e,AXIS]`,
/// `_MIN`, `_MAX`, `_IS_MODULO`. Requires MD38000 $MA_MM_ENC_COMP_MAX_POINTS ≥ n and MD32700
/// $MA_ENC_COMP_ENABLE[e] = 1 on the control.
struct SiemensEecTable {
  int encoder = 0;             ///< measuring system e: 0 or 1
  std::string axis;            ///< machine axis identifier (e.g. X1 or AX1)
  std::vector<double> values;  ///< compensation value (= error, mm) at MIN + N·STEP
  double min = 0.0;            ///< $AA_ENC_COMP_MIN, mm
  double step = 0.0;           ///< $AA_ENC_COMP_STEP, mm, > 0
  double max = 0.0;            ///< $AA_ENC_COMP_MAX = MIN + STEP·(n − 1), mm
  bool modulo = false;         ///< $AA_ENC_COMP_IS_MODULO
  /// Throws pkm::InvalidArgument unless encoder is 0/1, the axis a valid identifier, n ≥ 2,
  /// values finite, step > 0 and |MIN + STEP·(n−1) − MAX| ≤ 1e-6 mm.
  void validate() const;
  /// The compensation value at commanded position x: linear interpolation, first/last value outside
  /// [MIN, MAX] (with modulo: x wrapped into [MIN, MAX)). Throws pkm::InvalidArgument for NaN.
  [[nodiscard]] double valueAt(double x) const;
  /// Where the axis is sent for commanded position x: x − valueAt(x) (a positive value moves the
  /// axis in −).
  [[nodiscard]] double axisCommand(double x) const { return x - valueAt(x); }
};

/// The EEC table of `table`: values = the bidirectional mean error x̄i (EEC has no direction; the
/// reversal remains for the backlash compensation MD32450). The table must be evenly spaced (use
/// fitToTarget with traits(TableFormat::kSiemensEec)); throws pkm::InvalidArgument otherwise, for
/// an invalid table or axis name.
[[nodiscard]] SiemensEecTable siemensEecFromTable(const AxisErrorTable& table, int encoder = 0);
/// The part program %_N_AX_EEC_INI ... M17 (numbers fixed-point, at most 9 decimals). Throws as
/// validate().
[[nodiscard]] std::string writeSiemensEec(const SiemensEecTable& table);
/// Parses such a part program (one table; `;` comments, `%_N_` name, CHANDATA, M17/M30 lines
/// allowed). Throws pkm::IoError "SOURCE:LINE: message" for an unknown or malformed line, a
/// repeated or missing point, mixed encoders or axes, or a table that fails validate().
[[nodiscard]] SiemensEecTable parseSiemensEec(const std::string& text, const std::string& source);

/// One CEC table t: `$AN_CEC[t,N]`, `$AN_CEC_INPUT_AXIS[t]=(AXIS)`, `$AN_CEC_OUTPUT_AXIS[t]`,
/// `$AN_CEC_STEP[t]`, `_MIN`, `_MAX`, `_DIRECTION`, `_MULT_BY_TABLE`, `_IS_MODULO`. Requires
/// MD18342 $MN_MM_CEC_MAX_POINTS[t] ≥ n and MD32710 $MA_CEC_ENABLE on the output axis.
struct SiemensCecTable {
  int index = 0;               ///< table index t ≥ 0
  std::string input_axis;      ///< base axis (the table's argument)
  std::string output_axis;     ///< compensation axis (the one corrected)
  std::vector<double> values;  ///< error of the output axis (mm) at input MIN + N·STEP
  double min = 0.0;            ///< $AN_CEC_MIN, mm (input axis)
  double step = 0.0;           ///< $AN_CEC_STEP, mm, > 0
  double max = 0.0;            ///< $AN_CEC_MAX = MIN + STEP·(n − 1)
  int direction = 0;           ///< 0 both, 1 only +, −1 only − travel of the input axis
  int mult_by_table = 0;       ///< table number to multiply with, 0 = off
  bool modulo = false;         ///< $AN_CEC_IS_MODULO
  /// Throws pkm::InvalidArgument as SiemensEecTable::validate, and for direction ∉ {−1, 0, 1},
  /// index < 0 or mult_by_table < 0.
  void validate() const;
  /// The value at input-axis position x (as SiemensEecTable::valueAt).
  [[nodiscard]] double valueAt(double x) const;
};

/// The CEC table of a straightness/sag table (values = error of the output axis). Evenly spaced
/// required (fitToTarget with traits(TableFormat::kSiemensCec)); throws pkm::InvalidArgument
/// otherwise.
[[nodiscard]] SiemensCecTable siemensCecFromTable(const CrossAxisTable& table, int index = 0);
/// The part program %_N_NC_CEC_INI ... M17. Throws as validate().
[[nodiscard]] std::string writeSiemensCec(const SiemensCecTable& table);
/// Parses such a part program (one table). Throws pkm::IoError "SOURCE:LINE: message".
[[nodiscard]] SiemensCecTable parseSiemensCec(const std::string& text, const std::string& source);

}  // namespace pkm::compensation
