#include "stats/report.h"

#include <cmath>
#include <cstdio>

#include "stats/polynomial.h"

namespace repose::stats {

namespace {

// Columns keep at least one space between them when a value is wider than its column.
std::string pad(const std::string& s, int width, bool right) {
  if (static_cast<int>(s.size()) >= width) return right ? " " + s : s + " ";
  std::string fill(static_cast<size_t>(width) - s.size(), ' ');
  return right ? fill + s : s + fill;
}

std::string anova_line(const AnovaRow& r, const std::string& label, bool significance) {
  std::string line = pad(label, 22, false) + pad(format_value(r.ss), 14, true) +
                     pad(std::to_string(r.df), 5, true) + pad(format_value(r.ms), 14, true) +
                     pad(format_value(r.f), 10, true) + pad(std::isnan(r.p) ? "" : format_p(r.p), 10, true);
  if (significance && !std::isnan(r.p)) line += r.p < 0.05 ? "  significant" : "  not significant";
  return line + "\n";
}

}  // namespace

std::string format_p(double p) {
  if (std::isnan(p)) return "";
  if (p < 1e-4) return "< 0.0001";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4f", p);
  return buf;
}

std::string format_value(double v) {
  if (std::isnan(v)) return "";
  char buf[48];
  std::snprintf(buf, sizeof buf, (std::fabs(v) >= 1e-4 && std::fabs(v) < 1e7) || v == 0 ? "%.5g" : "%.4e", v);
  return buf;
}

std::string format_anova(const ResponseSurface& fit, const std::vector<std::string>& names,
                         const std::string& model_name) {
  std::string s = "ANOVA for the " + model_name + " model [" +
                  (fit.ss_type == SumOfSquaresType::partial ? "partial sum of squares - Type III"
                                                            : "sequential sum of squares - Type I") +
                  "]\n";
  s += pad("Source", 22, false) + pad("Sum of Squares", 14, true) + pad("df", 5, true) +
       pad("Mean Square", 14, true) + pad("F Value", 10, true) + pad("p-value", 10, true) + "\n";
  s += anova_line(fit.model, "Model", true);
  for (size_t t = 0; t < fit.term_rows.size(); ++t) {
    const Term& term = fit.terms[t + 1];
    std::string label = "  " + fit.term_rows[t].source;
    if (term.order() == 1) {
      for (size_t i = 0; i < term.powers.size(); ++i)
        if (term.powers[i] == 1 && i < names.size() && names[i] != fit.term_rows[t].source)
          label.append("-").append(names[i]);  // "A-mu_s", but just "A" when the column is A
    }
    s += anova_line(fit.term_rows[t], label, false);
  }
  s += anova_line(fit.residual, "Residual", false);
  if (fit.lack_of_fit) s += anova_line(*fit.lack_of_fit, "  Lack of Fit", true);
  if (fit.pure_error) s += anova_line(*fit.pure_error, "  Pure Error", false);
  s += anova_line(fit.total, "Cor Total", false);
  return s;
}

std::string format_fit_statistics(const ResponseSurface& fit) {
  const FitStatistics& st = fit.stats;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "Std. Dev.  %-12s R-Squared       %.4f\n"
                "Mean       %-12s Adj R-Squared   %.4f\n"
                "C.V. %%     %-12s Pred R-Squared  %s\n"
                "PRESS      %-12s Adeq Precision  %.3f\n",
                format_value(st.std_dev).c_str(), st.r2, format_value(st.mean).c_str(), st.adj_r2,
                format_value(st.cv_percent).c_str(),
                std::isnan(st.pred_r2) ? "n/a" : format_value(st.pred_r2).c_str(),
                std::isnan(st.press) ? "n/a" : format_value(st.press).c_str(), st.adeq_precision);
  return buf;
}

std::string format_coefficients(const ResponseSurface& fit) {
  std::string s = pad("Term", 12, false) + pad("Coefficient", 14, true) + pad("Std. Error", 14, true) +
                  pad("VIF", 8, true) + "\n";
  for (const auto& c : fit.coefficients) {
    char vif[32];
    std::snprintf(vif, sizeof vif, "%.2f", c.vif);
    s += pad(c.term, 12, false) + pad(format_value(c.estimate), 14, true) +
         pad(format_value(c.std_error), 14, true) + pad(c.term == "Intercept" ? "" : vif, 8, true) + "\n";
  }
  return s;
}

std::string format_equations(const ResponseSurface& fit, const std::string& response,
                             const std::vector<std::string>& names, const std::vector<Factor>& ranges) {
  std::string s = "Final equation in terms of coded factors:\n  " +
                  format_equation(fit.polynomial(), response) + "\n";
  std::string legend;
  for (size_t i = 0; i < names.size(); ++i) legend += "  " + factor_letter(static_cast<int>(i)) + " = " + names[i] + "\n";
  s += legend;
  if (!ranges.empty()) {
    s += "Final equation in terms of actual factors:\n  " +
         format_equation(to_actual_units(fit.polynomial(), ranges), response, names, 6) + "\n";
  }
  return s;
}

}  // namespace repose::stats
