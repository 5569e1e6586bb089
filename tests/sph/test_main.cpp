#define BOOST_TEST_MODULE sph
#include <boost/test/unit_test.hpp>
