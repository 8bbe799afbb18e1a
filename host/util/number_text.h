// The one home of how numbers become text in messages, reports and files: printf's %g with a
// number of significant digits, and the shortest text that reads back as the same double.
#pragma once
#include <string>

namespace repose {

// printf("%.<digits>g"): "0.3", "1.5e-05", "inf", "-0".
std::string format_g(double value, int digits = 6);

// The shortest of %.15g .. %.17g that reads back as the same double: exact, yet "0.3".
std::string exact_number(double value);

}  // namespace repose
