#define BOOST_TEST_MODULE analytic
#include <boost/test/unit_test.hpp>
