// A design factor and its coding: the actual values `low` and `high` are coded -1 and +1.
#pragma once
#include <string>
#include <vector>

namespace repose::stats {

struct Factor {
  std::string name;
  double low = -1;
  double high = 1;

  double centre() const { return 0.5 * (low + high); }
  double half_range() const { return 0.5 * (high - low); }
  double to_actual(double coded) const { return centre() + coded * half_range(); }
  double to_coded(double actual) const { return (actual - centre()) / half_range(); }
};

// "NAME:LOW:HIGH" -> Factor. Throws DesignError when malformed or when LOW >= HIGH.
Factor parse_factor(const std::string& spec);
// Comma-separated list of factor specs; names must be distinct.
std::vector<Factor> parse_factors(const std::string& list);
// "LOW:HIGH" for a factor whose name is known already.
Factor parse_range(const std::string& name, const std::string& range);

// Throws DesignError unless low < high and both are finite.
void check_range(const Factor& f);

std::vector<std::string> split(const std::string& s, char sep);

}  // namespace repose::stats
