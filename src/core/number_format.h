#pragma once
// Numbers as text in file names, manifests and CSV files.

#include <string>

namespace countershade {

// "0.02", "1.25": the shortest text that reads back as the same grid value (within 1e-12).
std::string format_value(double v);

// v rounded to `decimals` decimal places, for values reported rather than read back.
double round_to(double v, int decimals);

}  // namespace countershade
