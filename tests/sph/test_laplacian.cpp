// Fig. 3 of Afrasiabi et al. (2021): Laplacian of x^2 + y^2 on 21 x 21 particles in [-1,1]^2.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <iostream>

#include "cutbench/sph/runners.hpp"

using namespace cutbench::sph;
namespace tt = boost::test_tools;

BOOST_AUTO_TEST_SUITE(fig03_laplacian)

BOOST_AUTO_TEST_CASE(brookshaw_and_fmfs_on_regular_lattice) {
  const auto r = laplacian_reconstruction(21, 1.5, 0.0);
  std::cout << "Fig3 regular: Brookshaw interior mean " << r.brookshaw_interior_mean << " corner "
            << r.brookshaw_corner << " FMFS max |err| " << r.fmfs_max_abs_error << "\n";
  BOOST_TEST(std::abs(r.brookshaw_interior_mean - 4.027) < 0.01);
  BOOST_TEST(std::abs(r.brookshaw_corner - (-22.12)) < 0.01);
  BOOST_TEST(r.fmfs_irregular == 0.0);
  BOOST_TEST(r.fmfs_max_abs_error < 1e-8);
}

BOOST_AUTO_TEST_CASE(fmfs_exact_on_jittered_lattice) {
  for (double amp : {0.1, 0.25}) {
    const auto r = laplacian_reconstruction(21, 1.5, amp, 42);
    std::cout << "Fig3 jitter " << amp << ": FMFS max |err| " << r.fmfs_max_abs_error
              << ", Brookshaw max |err| " << r.brookshaw_max_abs_error << "\n";
    BOOST_TEST(r.fmfs_irregular == 0.0);
    BOOST_TEST(r.fmfs_max_abs_error < 1e-8);
  }
}

BOOST_AUTO_TEST_SUITE_END()
