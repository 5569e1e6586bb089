#define BOOST_TEST_MODULE common
#include <boost/test/unit_test.hpp>

#include <limits>

#include "cutbench/common/errors.hpp"
#include "cutbench/common/model.hpp"
#include "cutbench/common/units.hpp"

using namespace cutbench;

BOOST_AUTO_TEST_CASE(parse_quantities_to_si) {
  BOOST_TEST(parse_quantity("2 mm", Dim::length, "h") == 2e-3, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(parse_quantity("2mm", Dim::length, "h") == 2e-3, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(parse_quantity("0.5", Dim::length, "h") == 0.5);
  BOOST_TEST(parse_quantity("180 deg", Dim::angle, "rake") == 3.14159265358979323846,
             boost::test_tools::tolerance(1e-14));
  BOOST_TEST(parse_quantity("25 MPa", Dim::stress, "sigma_y") == 25e6);
  BOOST_TEST(parse_quantity("2000 J/m^2", Dim::force_per_width, "G_c") == 2000.0);
  BOOST_TEST(parse_quantity("1.5 N/mm", Dim::energy_per_area, "F") == 1500.0);
  BOOST_TEST(parse_quantity("20 degC", Dim::temperature, "T") == 293.15, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(wrong_unit_names_the_field) {
  try {
    parse_quantity("2 MPa", Dim::length, "h");
    BOOST_FAIL("expected InputError");
  } catch (const InputError& e) {
    BOOST_TEST(e.field() == "h");
    BOOST_TEST(std::string(e.what()).find("wrong unit") != std::string::npos);
  }
  BOOST_CHECK_THROW(parse_quantity("2 furlongs", Dim::length, "h"), InputError);
  BOOST_CHECK_THROW(parse_quantity("abc", Dim::length, "h"), InputError);
}

BOOST_AUTO_TEST_CASE(validate_ranges_and_unknown_keys) {
  ModelSpec spec;
  spec.name = "toy";
  spec.params.push_back(param("E", Dim::stress, "modulus", std::nullopt, 0.0,
                              std::numeric_limits<double>::infinity(), false));  // E > 0, required
  auto rake = param("rake", Dim::angle, "rake angle");
  rake.min = -1.5707963267948966;
  rake.max = 1.5707963267948966;
  rake.min_inclusive = rake.max_inclusive = false;
  rake.default_value = 0.0;
  spec.params.push_back(rake);
  spec.evaluate = [](const Values& v) { return ModelResult{{{"x", v.at("E")}}, true, ""}; };

  BOOST_CHECK_NO_THROW(validate_params(spec, {{"E", 1.0}}));
  BOOST_CHECK_THROW(validate_params(spec, {{"E", -1.0}}), InputError);
  BOOST_CHECK_THROW(validate_params(spec, {{"E", 1.0}, {"rake", 1.6}}), InputError);
  BOOST_CHECK_THROW(validate_params(spec, {{"E", 1.0}, {"nu", 0.3}}), InputError);
  BOOST_CHECK_THROW(validate_params(spec, {}), InputError);
  try {
    validate_params(spec, {{"E", 1.0}, {"rake", 1.6}});
  } catch (const InputError& err) {
    BOOST_TEST(err.field() == "rake");
    BOOST_TEST(std::string(err.what()).find("90 deg") != std::string::npos);
  }
}
