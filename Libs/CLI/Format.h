#pragma once
// Locale-independent number formatting: the host process may run under any locale, and a module
// must neither depend on it nor change it.
#include <string>

namespace colonmap::cli {

// Shortest text that reads back to the same double, "C" locale style.
std::string FormatNumber(double value);
// Fixed number of decimals.
std::string FormatFixed(double value, int decimals);

}  // namespace colonmap::cli
