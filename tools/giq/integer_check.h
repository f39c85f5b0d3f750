#pragma once
// The check every integer option of the CLI that CLI11 would bend carries: CLI11 alone turns
// "-1" into 2^64 - 1 for an unsigned option and clamps "18446744073709551616" to it without a
// word. With this check the text must be a plain decimal integer within [lo, hi], or the
// command exits 2 naming the option and the range.

#include <CLI/CLI.hpp>

namespace giq::cli {

CLI::Validator integer_in(long double lo, long double hi);

}  // namespace giq::cli
