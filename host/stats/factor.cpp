#include "stats/factor.h"

#include <cmath>

#include "stats/csv_table.h"
#include "stats/errors.h"

namespace repose::stats {

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : s) {
    if (c == sep) {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

void check_range(const Factor& f) {
  if (!std::isfinite(f.low) || !std::isfinite(f.high))
    throw DesignError("factor '" + f.name + "': range must be finite");
  if (!(f.low < f.high))
    throw DesignError("factor '" + f.name + "': range reversed or empty (low " +
                      std::to_string(f.low) + " must be below high " + std::to_string(f.high) + ")");
}

Factor parse_range(const std::string& name, const std::string& range) {
  auto parts = split(range, ':');
  Factor f;
  f.name = name;
  if (parts.size() != 2 || !parse_number(parts[0], f.low) || !parse_number(parts[1], f.high))
    throw DesignError("factor '" + name + "': range '" + range + "' is not LOW:HIGH");
  check_range(f);
  return f;
}

Factor parse_factor(const std::string& spec) {
  auto colon = spec.find(':');
  if (colon == std::string::npos || colon == 0)
    throw DesignError("factor '" + spec + "' is not NAME:LOW:HIGH");
  return parse_range(spec.substr(0, colon), spec.substr(colon + 1));
}

std::vector<Factor> parse_factors(const std::string& list) {
  std::vector<Factor> out;
  for (const auto& spec : split(list, ',')) {
    Factor f = parse_factor(spec);
    for (const auto& g : out)
      if (g.name == f.name) throw DesignError("factor '" + f.name + "' is given twice");
    out.push_back(f);
  }
  return out;
}

}  // namespace repose::stats
