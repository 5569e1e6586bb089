#define BOOST_TEST_MODULE efg
#include <boost/test/unit_test.hpp>
