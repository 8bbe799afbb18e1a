// The SI unit of a named quantity, for axis labels: a case key's last part ("material.grain.
// shear_modulus" -> "Pa"), an experiment response or a measured quantity ("rebound_height" ->
// "m", "angle" -> "deg"). "" for dimensionless quantities (restitution, friction coefficients).
#pragma once
#include <string>

namespace repose {

inline std::string quantity_unit(const std::string& name) {
  std::string last = name.substr(name.find_last_of('.') + 1);
  auto ends = [&](const char* suffix) {
    std::string s = suffix;
    return last.size() >= s.size() && last.compare(last.size() - s.size(), s.size(), s) == 0;
  };
  if (last == "tilt_rate_deg") return "deg/s";
  if (ends("_deg") || ends("angle") || ends("angle_3d") || ends("angle_front") || ends("angle_views_sd")) return "deg";
  if (ends("modulus")) return "Pa";
  if (last == "cohesion_energy_density") return "J/m^3";
  if (ends("density")) return "kg/m^3";
  if (ends("_speed") || last == "velocity") return "m/s";
  if (ends("_time") || last == "dt" || last == "t") return "s";
  if (ends("height") || ends("distance") || last == "radius" || last == "skin" || ends("_length")) return "m";
  if (last == "mass") return "kg";
  return "";
}

// "name (unit)", or the name alone for a dimensionless quantity.
inline std::string quantity_label(const std::string& name) {
  std::string unit = quantity_unit(name);
  return unit.empty() ? name : name + " (" + unit + ")";
}

}  // namespace repose
