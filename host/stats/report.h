// Text reports laid out like Design-Expert's: the ANOVA table (Source, Sum of Squares, df,
// Mean Square, F Value, p-value), the fit statistics, the coefficient table and the equations
// in coded and in actual units.
#pragma once
#include <string>
#include <vector>

#include "stats/anova.h"
#include "stats/factor.h"

namespace repose::stats {

// "< 0.0001" below 1e-4, else four decimals, as Design-Expert prints p values.
std::string format_p(double p);
// Five significant digits, no exponent for ordinary magnitudes; "" for NaN.
std::string format_value(double v);

std::string format_anova(const ResponseSurface& fit, const std::vector<std::string>& factor_names,
                         const std::string& model_name);
std::string format_fit_statistics(const ResponseSurface& fit);
std::string format_coefficients(const ResponseSurface& fit);
// Both equations; the actual one only when `ranges` is not empty.
std::string format_equations(const ResponseSurface& fit, const std::string& response,
                             const std::vector<std::string>& factor_names,
                             const std::vector<Factor>& ranges);

}  // namespace repose::stats
