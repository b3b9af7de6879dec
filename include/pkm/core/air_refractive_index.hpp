/// @file
/// @brief The refractive index of air for length interferometry: Edlén's equation (Metrologia
/// 2:71, 1966) as updated by Birch and Downs (Metrologia 30:155, 1993; 31:315, 1994) with the
/// water-vapour term scaled by temperature as NIST's Engineering Metrology Toolbox modifies it
/// (J. A. Stone, J. H. Zimmerman, "Index of Refraction of Air", Appendix A-IV), and the saturation
/// vapour pressure of water (IAPWS-IF97 over water, IAPWS 1993 sublimation over ice; Appendix
/// A-I). A laser interferometer's wavelength in air is λ_vac / n; an error δn of the index is a
/// relative length error −δn (ISO 230-2:2014 Annex A, ISO/TR 230-9 §6: "environmental
/// compensation"). docs/analysis.md, "Refractive index of air".
#pragma once

#include <string>

namespace pkm {

/// The state of the air in the beam path.
struct AirConditions {
  double temperature_c = 20.0;    ///< air temperature t, °C (validity of the equation: −40..100)
  double pressure_pa = 101325.0;  ///< absolute pressure p, Pa (60 000..140 000)
  double relative_humidity = 50.0;  ///< relative humidity RH, % (0..100)

  /// True when every field is finite and inside the equation's range; otherwise false with the
  /// reason in *why (if given).
  [[nodiscard]] bool isValid(std::string* why = nullptr) const;
};

/// HeNe laser vacuum wavelength used when none is given, µm (633 nm, iodine-stabilised value
/// 632.991 nm rounded as laser calibrators state it).
inline constexpr double kHeNeVacuumWavelengthUm = 0.632991;

/// Saturation vapour pressure of water at `temperature_c` (°C), Pa: over liquid water for
/// t >= 0 °C (IAPWS-IF97 region 4 saturation equation), over ice below (IAPWS 1993).
/// Throws pkm::InvalidArgument for a temperature outside −100..373 °C or not finite.
[[nodiscard]] double saturationVapourPressure(double temperature_c);

/// n of moist air by the modified Edlén equation at the vacuum wavelength
/// `vacuum_wavelength_um` (µm, 0.3..1.7): dry-air dispersion (n−1)_s = [8342.54 + 2406147/(130 −
/// σ²) + 15998/(38.9 − σ²)]·10⁻⁸, density factor p·[1 + 10⁻⁸(0.601 − 0.00972 t)p] /
/// [96095.43 (1 + 0.003661 t)], water term −10⁻¹⁰·(292.75/T)(3.7345 − 0.0401 σ²)·p_v with σ =
/// 1/λ in µm⁻¹, T in K and the vapour pressure p_v = RH/100 × saturationVapourPressure(t), Pa.
/// Agrees with NIST's tabulated values to 1e-9 (tests). Throws pkm::InvalidArgument for invalid
/// conditions or a wavelength outside 0.3..1.7 µm.
[[nodiscard]] double refractiveIndexEdlen(const AirConditions& air,
                                          double vacuum_wavelength_um = kHeNeVacuumWavelengthUm);

/// The partial derivatives of the modified Edlén n with respect to the air's state at `air`
/// (central differences): how much a sensor error moves the compensated wavelength.
struct AirIndexSensitivity {
  double per_kelvin = 0.0;      ///< ∂n/∂t, 1/K (about −0.93e-6 at 20 °C)
  double per_pascal = 0.0;      ///< ∂n/∂p, 1/Pa (about +2.7e-9)
  double per_percent_rh = 0.0;  ///< ∂n/∂RH, 1/% (about −8.6e-9 at 20 °C)
};

/// ∂n/∂t, ∂n/∂p and ∂n/∂RH at `air`. Throws as refractiveIndexEdlen.
[[nodiscard]] AirIndexSensitivity edlenSensitivity(
    const AirConditions& air, double vacuum_wavelength_um = kHeNeVacuumWavelengthUm);

}  // namespace pkm
