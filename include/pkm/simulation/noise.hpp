/// @file
/// @brief Noise model of an instrument reading: a constant Gaussian term, a term proportional to
/// the measured length (ppm), and quantisation to the instrument's resolution (instrument
/// datasheets).
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "pkm/simulation/random.hpp"

namespace pkm::simulation {

/// How an instrument corrupts a true reading. Every field 0 means an ideal instrument, which
/// returns the true reading unchanged and draws nothing from its stream.
struct NoiseModel {
  /// Standard deviation of the constant Gaussian term, in the reading's unit (e.g. mm; for a
  /// Renishaw XL-80 linear reading a few nm, 5e-6 to 2e-5 mm).
  double sigma = 0.0;
  /// Standard deviation of the length-proportional term, in parts per million of `length` (the
  /// measured length, see apply()). The XL-80's ±0.5 ppm (k = 2) is sigma_ppm = 0.25. A laser's
  /// ppm accuracy is its environmental compensation's, which holds over a test: a line
  /// measurement draws it once per line as a scale error (drawScale); apply() without a scale
  /// draws it per reading.
  double sigma_ppm = 0.0;
  /// Resolution: the reading is rounded to the nearest multiple of it (0: no rounding). XL-80
  /// linear: 1 nm = 1e-6 mm.
  double resolution = 0.0;
  /// A perfect instrument: apply() returns the truth, unrounded, yet draws its variate as the
  /// noisy instrument would, so that every later draw of the stream (targets, the machine's
  /// non-repeatable state) is the noisy twin's. The truth runs of `pkm validate coverage`
  /// (workflow/coverage.hpp).
  bool perfect = false;

  /// Throws pkm::InvalidArgument when a field is negative or not finite.
  void validate() const;
  /// The standard deviation of the Gaussian part for a measured length `length` (same unit as the
  /// reading for a linear reading): sqrt(sigma² + (sigma_ppm·1e-6·|length|)²).
  [[nodiscard]] double totalSigma(double length) const;
  /// The reading an instrument shows for the true value `truth` over the measured length
  /// `length`: truth + N(0, totalSigma(length)), then rounded to `resolution` (`perfect`: the
  /// truth itself). Draws one normal variate from `rng` when totalSigma(length) > 0 and none
  /// otherwise.
  [[nodiscard]] double apply(double truth, double length, RandomStream& rng) const;
  /// The scale error of one measured line (dimensionless): N(0, sigma_ppm·1e-6), one normal
  /// variate drawn when sigma_ppm > 0 and none otherwise; 0 for a perfect instrument (drawn all
  /// the same, so that the stream stays the noisy twin's).
  [[nodiscard]] double drawScale(RandomStream& rng) const;
  /// The scale error `z` standard deviations from 0: z·sigma_ppm·1e-6 (0 for a perfect
  /// instrument). For a scale drawn once per session (simulateLine with a scale_z).
  [[nodiscard]] double scaleFor(double z) const;
  /// The reading of a line whose scale error is `scale` (drawScale): truth + scale·length +
  /// N(0, sigma), rounded to `resolution` (`perfect`: the truth). Draws one normal variate when
  /// sigma > 0 and none otherwise.
  [[nodiscard]] double apply(double truth, double length, double scale, RandomStream& rng) const;
};

/// The noise of a named instrument, from datasheet values (typical Renishaw XL-80 figures; k = 2
/// accuracies are halved to a standard deviation). Units: mm for the linear and straightness
/// presets, rad for the angular one.
/// - "ideal": no noise, no rounding.
/// - "xl80-linear": 10 nm per reading, 0.25 ppm of the travel (±0.5 ppm, k = 2; a line's scale
///   error), resolution 1 nm.
/// - "xl80-straightness": 0.25 µm (±0.5 µm, short range), resolution 0.01 µm.
/// - "xl80-angular": 0.05 µrad (±0.1 µm/m), resolution 0.01 µrad.
/// - "dial-gauge": 0.5 µm, resolution 1 µm (a 1 µm dial gauge, Lee et al., "Development of a
///   Parallel-Typed CNC Machine").
/// std::nullopt for another name.
[[nodiscard]] std::optional<NoiseModel> instrumentNoise(std::string_view name);
/// The names instrumentNoise knows.
[[nodiscard]] std::vector<std::string_view> instrumentNoiseNames();

}  // namespace pkm::simulation
