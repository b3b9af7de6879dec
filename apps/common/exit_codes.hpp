/// @file
/// @brief The exit codes every pkm program uses (docs/formats.md, "Exit codes").
#pragma once

namespace pkm::cli {

/// Exit codes: the job ran and a check failed or a target was missed; a usage or input error; an
/// internal error (a bug: please report it).
inline constexpr int kExitCheckFailed = 1;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitInternal = 3;

/// The exit-code scheme, as `--help` states it.
inline constexpr const char* kExitCodesHelp =
    "Exit codes: 0 success; 1 the job ran and a check failed or a target was missed; 2 usage or "
    "input error; 3 internal error.";

}  // namespace pkm::cli
