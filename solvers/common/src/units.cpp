#include "cutbench/common/units.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>

#include "cutbench/common/errors.hpp"

namespace cutbench {
namespace {

const std::map<std::string, UnitInfo, std::less<>>& unit_table() {
  constexpr double pi = 3.14159265358979323846;
  static const std::map<std::string, UnitInfo, std::less<>> table = {
      {"1", {1.0, 0.0, Dim::dimensionless}},
      {"-", {1.0, 0.0, Dim::dimensionless}},
      {"%", {0.01, 0.0, Dim::dimensionless}},
      {"m", {1.0, 0.0, Dim::length}},
      {"mm", {1e-3, 0.0, Dim::length}},
      {"um", {1e-6, 0.0, Dim::length}},
      {"µm", {1e-6, 0.0, Dim::length}},
      {"cm", {1e-2, 0.0, Dim::length}},
      {"rad", {1.0, 0.0, Dim::angle}},
      {"deg", {pi / 180.0, 0.0, Dim::angle}},
      {"Pa", {1.0, 0.0, Dim::stress}},
      {"kPa", {1e3, 0.0, Dim::stress}},
      {"MPa", {1e6, 0.0, Dim::stress}},
      {"N/mm^2", {1e6, 0.0, Dim::stress}},
      {"N/mm2", {1e6, 0.0, Dim::stress}},
      {"GPa", {1e9, 0.0, Dim::stress}},
      {"N", {1.0, 0.0, Dim::force}},
      {"kN", {1e3, 0.0, Dim::force}},
      {"N/m", {1.0, 0.0, Dim::force_per_width}},
      {"N/mm", {1e3, 0.0, Dim::force_per_width}},
      {"J/m^2", {1.0, 0.0, Dim::force_per_width}},
      {"J/m2", {1.0, 0.0, Dim::force_per_width}},
      {"kJ/m^2", {1e3, 0.0, Dim::force_per_width}},
      {"s", {1.0, 0.0, Dim::time}},
      {"ms", {1e-3, 0.0, Dim::time}},
      {"us", {1e-6, 0.0, Dim::time}},
      {"m/s", {1.0, 0.0, Dim::velocity}},
      {"m/min", {1.0 / 60.0, 0.0, Dim::velocity}},
      {"mm/min", {1e-3 / 60.0, 0.0, Dim::velocity}},
      {"kg/m^3", {1.0, 0.0, Dim::density}},
      {"kg/m3", {1.0, 0.0, Dim::density}},
      {"g/cm^3", {1e3, 0.0, Dim::density}},
      {"g/cm3", {1e3, 0.0, Dim::density}},
      {"K", {1.0, 0.0, Dim::temperature}},
      {"degC", {1.0, 273.15, Dim::temperature}},
      {"W/m/K", {1.0, 0.0, Dim::conductivity}},
      {"W/(m K)", {1.0, 0.0, Dim::conductivity}},
      {"J/kg/K", {1.0, 0.0, Dim::specific_heat}},
      {"J/(kg K)", {1.0, 0.0, Dim::specific_heat}},
      {"W/m^2/K", {1.0, 0.0, Dim::heat_transfer}},
      {"W/(m^2 K)", {1.0, 0.0, Dim::heat_transfer}},
      {"N m/m", {1.0, 0.0, Dim::moment_per_width}},
      {"Pa m^0.5", {1.0, 0.0, Dim::stress_intensity}},
      {"MPa m^0.5", {1e6, 0.0, Dim::stress_intensity}},
      {"MPa sqrt(m)", {1e6, 0.0, Dim::stress_intensity}},
      {"1/m", {1.0, 0.0, Dim::inverse_length}},
      {"1/mm", {1e3, 0.0, Dim::inverse_length}},
      {"1/s", {1.0, 0.0, Dim::strain_rate}},
  };
  return table;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

}  // namespace

std::string si_unit(Dim d) {
  switch (d) {
    case Dim::dimensionless: return "1";
    case Dim::length: return "m";
    case Dim::angle: return "rad";
    case Dim::stress: return "Pa";
    case Dim::force: return "N";
    case Dim::force_per_width: return "N/m";
    case Dim::energy_per_area: return "J/m^2";
    case Dim::time: return "s";
    case Dim::velocity: return "m/s";
    case Dim::density: return "kg/m^3";
    case Dim::temperature: return "K";
    case Dim::conductivity: return "W/(m K)";
    case Dim::specific_heat: return "J/(kg K)";
    case Dim::heat_transfer: return "W/(m^2 K)";
    case Dim::moment_per_width: return "N m/m";
    case Dim::stress_intensity: return "Pa m^0.5";
    case Dim::inverse_length: return "1/m";
    case Dim::strain_rate: return "1/s";
  }
  return "?";
}

std::string dim_name(Dim d) {
  switch (d) {
    case Dim::dimensionless: return "dimensionless";
    case Dim::length: return "length";
    case Dim::angle: return "angle";
    case Dim::stress: return "stress";
    case Dim::force: return "force";
    case Dim::force_per_width: return "force per width";
    case Dim::energy_per_area: return "energy per area";
    case Dim::time: return "time";
    case Dim::velocity: return "velocity";
    case Dim::density: return "density";
    case Dim::temperature: return "temperature";
    case Dim::conductivity: return "thermal conductivity";
    case Dim::specific_heat: return "specific heat";
    case Dim::heat_transfer: return "heat transfer coefficient";
    case Dim::moment_per_width: return "moment per width";
    case Dim::stress_intensity: return "stress intensity";
    case Dim::inverse_length: return "inverse length";
    case Dim::strain_rate: return "strain rate";
  }
  return "?";
}

bool same_dimension(Dim a, Dim b) {
  auto canon = [](Dim d) { return d == Dim::energy_per_area ? Dim::force_per_width : d; };
  return canon(a) == canon(b);
}

UnitInfo unit_info(std::string_view symbol, const std::string& field) {
  const auto& t = unit_table();
  auto it = t.find(trim(symbol));
  if (it == t.end()) {
    throw InputError(field, "unknown unit '" + std::string(symbol) + "'");
  }
  return it->second;
}

double parse_quantity(std::string_view text, Dim expected, const std::string& field) {
  std::string s(trim(text));
  if (s.empty()) throw InputError(field, "empty value (expected a " + dim_name(expected) + ")");
  const char* begin = s.c_str();
  char* end = nullptr;
  double v = std::strtod(begin, &end);
  if (end == begin) {
    throw InputError(field, "'" + s + "' is not a number with an optional unit (expected a " +
                                dim_name(expected) + " in " + si_unit(expected) + ")");
  }
  if (!std::isfinite(v)) throw InputError(field, "value must be finite, got '" + s + "'");
  std::string_view unit = trim(std::string_view(end));
  if (unit.empty()) return v;
  UnitInfo u = unit_info(unit, field);
  if (!same_dimension(u.dim, expected)) {
    throw InputError(field, "wrong unit '" + std::string(unit) + "' (a " + dim_name(u.dim) +
                                "); expected a " + dim_name(expected) + " such as " +
                                si_unit(expected));
  }
  return v * u.factor + u.offset;
}

double from_si(double si_value, std::string_view unit, const std::string& field) {
  UnitInfo u = unit_info(unit, field);
  return (si_value - u.offset) / u.factor;
}

double to_si(double value, std::string_view unit, const std::string& field) {
  UnitInfo u = unit_info(unit, field);
  return value * u.factor + u.offset;
}

}  // namespace cutbench
