#include "stats/fit_file.h"

#include <fstream>
#include <sstream>

#include "stats/errors.h"

namespace repose::stats {

namespace {

constexpr const char* kFormat = "repose-fit/1";

Json row_json(const AnovaRow& r) {
  Json o = Json::object();
  o.set("source", r.source);
  o.set("ss", r.ss);
  o.set("df", r.df);
  o.set("ms", r.ms);
  o.set("f", r.f);
  o.set("p", r.p);
  return o;
}

Json numbers(const Eigen::VectorXd& v) {
  Json a = Json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push(v[i]);
  return a;
}

Json polynomial_json(const Polynomial& p) {
  Json o = Json::object(), terms = Json::array(), coef = Json::array();
  for (size_t i = 0; i < p.terms.size(); ++i) {
    terms.push(term_name(p.terms[i]));
    coef.push(p.coef[i]);
  }
  o.set("terms", terms);
  o.set("coefficients", coef);
  return o;
}

}  // namespace

Json fit_to_json(const ResponseSurface& fit, const DataSet& data, const std::string& table_source,
                 const std::string& model_name, const std::vector<RemovedTerm>& removed) {
  Json j = Json::object();
  j.set("format", kFormat);
  j.set("table", table_source);
  j.set("response", data.response);
  Json factors = Json::array();
  for (size_t i = 0; i < data.factor_names.size(); ++i) {
    Json f = Json::object();
    f.set("name", data.factor_names[i]);
    f.set("letter", factor_letter(static_cast<int>(i)));
    if (!data.ranges.empty()) {
      f.set("low", data.ranges[i].low);
      f.set("high", data.ranges[i].high);
    }
    factors.push(f);
  }
  j.set("factors", factors);
  j.set("coded_min", numbers(data.coded.colwise().minCoeff().transpose()));
  j.set("coded_max", numbers(data.coded.colwise().maxCoeff().transpose()));
  j.set("response_range", numbers((Eigen::VectorXd(2) << fit.y_min, fit.y_max).finished()));
  j.set("model", model_name);
  j.set("sum_of_squares", fit.ss_type == SumOfSquaresType::partial ? "partial (Type III)" : "sequential (Type I)");
  j.set("coded_equation", polynomial_json(fit.polynomial()));
  if (!data.ranges.empty()) j.set("actual_equation", polynomial_json(to_actual_units(fit.polynomial(), data.ranges)));
  Json anova = Json::array();
  anova.push(row_json(fit.model));
  for (const auto& r : fit.term_rows) anova.push(row_json(r));
  anova.push(row_json(fit.residual));
  if (fit.lack_of_fit) anova.push(row_json(*fit.lack_of_fit));
  if (fit.pure_error) anova.push(row_json(*fit.pure_error));
  anova.push(row_json(fit.total));
  j.set("anova", anova);
  Json st = Json::object();
  st.set("std_dev", fit.stats.std_dev);
  st.set("mean", fit.stats.mean);
  st.set("cv_percent", fit.stats.cv_percent);
  st.set("press", fit.stats.press);
  st.set("r2", fit.stats.r2);
  st.set("adj_r2", fit.stats.adj_r2);
  st.set("pred_r2", fit.stats.pred_r2);
  st.set("adeq_precision", fit.stats.adeq_precision);
  j.set("statistics", st);
  Json rem = Json::array();
  for (const auto& r : removed) {
    Json o = Json::object();
    o.set("term", r.term);
    o.set("p", r.p);
    rem.push(o);
  }
  j.set("removed_terms", rem);
  return j;
}

SavedFit saved_fit_from_json(const Json& j) {
  SavedFit s;
  s.source = j.source();
  const Json& format = j.at("format");
  if (format.string() != kFormat)
    throw InputError(j.source(), format.line(), format.column(),
                     "not a repose fit file (format '" + format.string() + "', expected '" + kFormat + "')");
  s.response = j.at("response").string();
  const auto& factors = j.at("factors").items();
  if (factors.empty()) throw InputError(j.source(), j.at("factors").line(), j.at("factors").column(), "no factors");
  const int k = static_cast<int>(factors.size());
  bool has_ranges = factors[0].has("low");
  for (const auto& f : factors) {
    s.factor_names.push_back(f.at("name").string());
    if (f.has("low") != has_ranges)
      throw InputError(j.source(), f.line(), f.column(), "either every factor has low/high or none has");
    if (has_ranges) {
      Factor r{s.factor_names.back(), f.at("low").number(), f.at("high").number()};
      try {
        check_range(r);
      } catch (const DesignError& e) {
        throw InputError(j.source(), f.line(), f.column(), e.what());
      }
      s.ranges.push_back(r);
    }
  }
  auto vec = [&](const char* key) {
    const Json& a = j.at(key);
    const auto& items = a.items();
    if (static_cast<int>(items.size()) != k)
      throw InputError(j.source(), a.line(), a.column(),
                       std::string("'") + key + "' needs one value per factor (" + std::to_string(k) + ")");
    Eigen::VectorXd v(k);
    for (int i = 0; i < k; ++i) v[i] = items[i].number();
    return v;
  };
  s.coded_min = vec("coded_min");
  s.coded_max = vec("coded_max");
  const Json& rr = j.at("response_range");
  if (rr.items().size() != 2) throw InputError(j.source(), rr.line(), rr.column(), "'response_range' needs [min, max]");
  s.y_min = rr.items()[0].number();
  s.y_max = rr.items()[1].number();
  const Json& eq = j.at("coded_equation");
  const auto& terms = eq.at("terms").items();
  const auto& coef = eq.at("coefficients").items();
  if (terms.size() != coef.size() || terms.empty())
    throw InputError(j.source(), eq.line(), eq.column(), "terms and coefficients differ in number");
  for (size_t i = 0; i < terms.size(); ++i) {
    try {
      s.coded.terms.push_back(parse_term(terms[i].string(), k));
    } catch (const ModelError& e) {
      throw InputError(j.source(), terms[i].line(), terms[i].column(), e.what());
    }
    s.coded.coef.push_back(coef[i].number());
  }
  return s;
}

SavedFit read_fit_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError(path, 0, 0, "cannot open file");
  std::ostringstream ss;
  ss << f.rdbuf();
  return saved_fit_from_json(Json::parse(ss.str(), path));
}

}  // namespace repose::stats
