#pragma once
// Units: every quantity inside cutbench is SI. Case files and the command line may give a value
// with a unit ("2 mm", "30 deg", "25 MPa"); parse_quantity converts it to SI and checks that the
// unit has the dimension the field expects, so "h = 2 MPa" is rejected naming the field.
#include <string>
#include <string_view>

namespace cutbench {

enum class Dim {
  dimensionless,
  length,
  angle,
  stress,           // Pa (also modulus, strength)
  force,            // N
  force_per_width,  // N/m (= J/m^2: the papers' F/b and G_c share it)
  energy_per_area,  // J/m^2 (alias of force_per_width, kept for clarity)
  time,
  velocity,
  density,
  temperature,
  conductivity,     // W/(m K)
  specific_heat,    // J/(kg K)
  heat_transfer,    // W/(m^2 K)
  moment_per_width, // N m / m = N
  stress_intensity, // Pa sqrt(m)
  inverse_length,   // 1/m (curvature)
  strain_rate,      // 1/s
};

// The SI unit symbol written into result files for a dimension.
std::string si_unit(Dim d);
std::string dim_name(Dim d);

// True when a and b measure the same thing (force_per_width and energy_per_area are one).
bool same_dimension(Dim a, Dim b);

struct Quantity {
  double si_value = 0.0;
  Dim dim = Dim::dimensionless;
};

// Parse "2.5", "2.5 mm", "2.5mm", "30 deg", "1e-3 m". A bare number is SI in the expected
// dimension. Throws InputError(field, ...) for an unknown unit or a dimension mismatch.
double parse_quantity(std::string_view text, Dim expected, const std::string& field);

// Factor and dimension of a unit symbol ("mm" -> 1e-3, length). Throws InputError if unknown.
struct UnitInfo {
  double factor;  // SI = value * factor (+ offset for temperatures)
  double offset;
  Dim dim;
};
UnitInfo unit_info(std::string_view symbol, const std::string& field);

// Convert an SI value to the given unit (for display and check records).
double from_si(double si_value, std::string_view unit, const std::string& field);
// Convert a value in the given unit to SI.
double to_si(double value, std::string_view unit, const std::string& field);

}  // namespace cutbench
