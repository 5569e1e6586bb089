// Frictionless single-shear-plane chip formation against Merchant (Figueiredo et al. 2024, Fig. 1).
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>

#include "cutbench/common/errors.hpp"
#include "cutbench/limit/cutting.hpp"

#include "chip_fixture.hpp"
#include "release_only.hpp"

using namespace cutbench::limit;

BOOST_AUTO_TEST_SUITE(limit_cutting)

BOOST_AUTO_TEST_CASE(geometry_formulas) {
  // Eq. 2 and Merchant at μ = 0, α = 0: φ = 45°, t2 = t1, F̄c = 2
  BOOST_TEST(std::abs(chip_thickness(1.0, M_PI / 4, 0.0) - 1.0) < 1e-14);
  BOOST_TEST(std::abs(merchant_shear_angle(0.0, 0.0) - M_PI / 4) < 1e-14);
  BOOST_TEST(std::abs(merchant_force_bar(M_PI / 4, 0.0, 0.0) - 2.0) < 1e-14);
  // Merchant's φ minimises F̄c(φ)
  const double a = 6.0 * M_PI / 180, mu = 0.4, pm = merchant_shear_angle(a, mu);
  BOOST_TEST(merchant_force_bar(pm, a, mu) < merchant_force_bar(pm + 0.01, a, mu));
  BOOST_TEST(merchant_force_bar(pm, a, mu) < merchant_force_bar(pm - 0.01, a, mu));
}

BOOST_AUTO_TEST_CASE(frictionless_chip_against_merchant) {
  // free surfaces traction-free and unconstrained (streamline = 0): without friction the
  // material leaves through the chip (top flux 0.06 at n = 8), see the frictional tests below
  for (double alpha_deg : {0.0, 6.0}) {
    const double alpha = alpha_deg * M_PI / 180;
    CuttingSetup c;
    c.streamline = 0;
    c.alpha = alpha;
    c.mu = 0.0;
    c.phi = merchant_shear_angle(alpha, 0.0);
    c.contact_length = c.t1 / std::cos(alpha);  // restricted tool, minimum contact length
    const double fm = merchant_force_bar(c.phi, alpha, 0.0);
    const double ffm = fm * std::tan(-alpha);  // Merchant's feed force at β = 0
    double prev = 1e9;
    for (int n : {4, 8}) {
      c.n = n;
      const auto r = solve_cutting(c);
      const double err = std::abs(r.fc_bar / fm - 1.0);
      BOOST_TEST_MESSAGE("alpha=" << alpha_deg << " n=" << n << " Fc_bar=" << r.fc_bar << " (Merchant " << fm
                                  << ") Ff_bar=" << r.ff_bar << " (Merchant " << ffm << ") it="
                                  << r.solution.socp.iterations << " t=" << r.solution.socp.seconds << "s");
      BOOST_TEST(r.solution.socp.status == SocpStatus::optimal);
      BOOST_TEST(err < prev);
      prev = err;
      BOOST_TEST(std::abs(r.ff_bar - ffm) < 0.02 * fm);
      // frictionless: no tangential stress on the rake face
      for (double t : r.tau) BOOST_TEST(std::abs(t) < 1e-6);
    }
    BOOST_TEST(prev < (alpha_deg == 0.0 ? 0.01 : 0.02));
  }
}

BOOST_AUTO_TEST_CASE(supernodal_and_up_looking_ldl_agree_on_a_frictional_chip) {
  // the Table 3 chip at t1 = 0.5 mm (mu = 0.4809, layer model, n = 6) with the associated Coulomb
  // cone (one SOCP, so that the sanitizer build stays quick): the two factorisations give the same
  // collapse load, contact pressures and stick zone
  CuttingSetup c = test::table3_chip_t1_05();
  c.coulomb_fixed_point = false;
  SocpSettings up, sn;
  up.backend = KktBackend::builtin;
  sn.backend = KktBackend::supernodal;
  const auto a = solve_cutting(c, up), b = solve_cutting(c, sn);
  BOOST_TEST(std::abs(a.fc_bar - b.fc_bar) < 1e-7 * a.fc_bar);
  BOOST_TEST(a.sigma_n.size() == b.sigma_n.size());
  double pmax = 0.0, diff = 0.0;
  for (std::size_t i = 0; i < a.sigma_n.size() && i < b.sigma_n.size(); ++i) {
    pmax = std::max(pmax, std::abs(a.sigma_n[i]));
    diff = std::max(diff, std::abs(a.sigma_n[i] - b.sigma_n[i]));
  }
  BOOST_TEST_MESSAGE("F_c bar " << a.fc_bar << " / " << b.fc_bar << ", max |d sigma_n| " << diff << " of " << pmax);
  BOOST_TEST(diff < 1e-4 * pmax);
  BOOST_TEST(a.stick_fraction == b.stick_fraction);
}

BOOST_AUTO_TEST_CASE(frictionless_chip_adaptive) {
  // α = 0, μ = 0, φ = 45°, l = 1.2 t1: dissipation-driven refinement from n = 4:
  // F̄c 2.033 (136 elements) → 2.007 with 343 elements after 5 steps (uniform n = 12: 2.005, 1032).
  CuttingSetup c;
  c.n = 4;
  c.contact_length = 1.2;
  c.streamline = 0;
  AdaptOptions opt;
  opt.steps = 5;
  const auto steps = adapt_limit(cutting_model(c).mesh, [&](Mesh m) { return cutting_model_on_mesh(std::move(m), c); }, opt);
  for (const auto& s : steps) BOOST_TEST_MESSAGE("adaptive chip: elements " << s.elements << " Fc_bar " << s.collapse);
  BOOST_TEST(std::abs(steps.back().collapse / 2.0 - 1.0) < 0.005);
  BOOST_TEST(steps.back().elements < 400);
}

BOOST_AUTO_TEST_CASE(measured_shear_angle_frictionless) {
  // single shear plane at φ = 45° (α = 0, μ = 0): the free-surface velocity turns at S.
  // The band is smeared over the elements next to OS: φ* = 43.7° at n = 8, 44.6° at n = 16.
  CuttingSetup c;
  c.n = 8;
  c.contact_length = 1.2;
  c.streamline = 0;
  const auto r = solve_cutting(c);
  const double ps = measured_shear_angle(c, r) * 180.0 / M_PI;
  BOOST_TEST_MESSAGE("phi* = " << ps << " deg for phi = 45 deg");
  BOOST_TEST(std::abs(ps - 45.0) < 2.0);
}

BOOST_AUTO_TEST_CASE(contact_length_search_frictionless) {
  // α = 0, μ = 0, φ = 45°: the normal stress at the end of the contact vanishes at l ≈ 1.2–1.3 t1
  // (n = 4: 1.234, n = 8: 1.266); the paper: "on the order of t1" without friction.
  CuttingSetup c;
  c.n = 4;
  c.streamline = 0;
  const auto r = search_contact_length(c);
  BOOST_TEST_MESSAGE("contact length " << r.contact_length << " after " << r.lengths.size() << " solves");
  BOOST_TEST(!r.restricted);
  BOOST_TEST(r.contact_length > 1.1);
  BOOST_TEST(r.contact_length < 1.4);
  BOOST_TEST(std::abs(end_normal_stress(r.final, r.contact_length)) < 0.05);
  BOOST_TEST(end_normal_stress(r.final, 1.0) < 0.0);  // compressive over the restricted length
}

BOOST_AUTO_TEST_CASE(frictional_chip_escapes_through_free_surface) {
  // The bug behind F̄c ≈ 2.08 and full sticking: with μ > 0 and traction-free, unconstrained
  // free surfaces, the cheapest mechanism of the imposed geometry pushes the whole inflow out
  // through the uncut top surface (a new 'chip' at ≈ 19°) and leaves the imposed chip at rest on
  // the tool; F̄c is then the frictionless value whatever μ. Steady state needs v·n = 0 there.
  CuttingSetup c;
  c.n = 6;
  c.mu = 0.2;
  c.phi = merchant_shear_angle(0.0, 0.2);
  c.contact_length = 1.5;
  c.streamline = 0;
  const auto free = solve_cutting(c);
  BOOST_TEST_MESSAGE("free surfaces: Fc_bar " << free.fc_bar << " flux top " << free.flux_top << " end " << free.flux_end
                                              << " stick " << free.stick_fraction);
  BOOST_TEST(free.flux_top > 0.9);
  BOOST_TEST(free.flux_end < 0.1);
  c.streamline = 1;
  const auto held = solve_cutting(c);
  BOOST_TEST_MESSAGE("top streamline: Fc_bar " << held.fc_bar << " flux top " << held.flux_top << " end "
                                               << held.flux_end << " stick " << held.stick_fraction);
  BOOST_TEST(std::abs(held.flux_top) < 0.02);
  BOOST_TEST(held.flux_end > 0.97);
  BOOST_TEST(std::abs(held.flux_top + held.flux_back + held.flux_end + held.flux_rake_free - 1.0) < 1e-6);  // incompressible
  BOOST_TEST(held.fc_bar > free.fc_bar + 0.2);
}

BOOST_AUTO_TEST_CASE(natural_separation_point) {
  // Contact over 4 t1: after the coupled first step the Coulomb steps (|r_t| ≤ μ p_k, r_n ≤ 0)
  // let the chip separate where the pressure vanishes (the fixed point also runs at μ = 0 here).
  // Frictionless, α = 0, φ = 45°, n = 4: l_sep = 1.0 t1 (the incremental search with permanent
  // contact gives 1.23; the paper: of the order of t1/cos α without friction); beyond l_sep σ_n ≈ 0.
  CuttingSetup c;
  c.n = 4;
  const auto nat = natural_contact_length(c, 4.0, 0.1);
  BOOST_TEST_MESSAGE("frictionless natural separation l = " << nat.contact_length);
  BOOST_TEST(nat.contact_length > 0.9);
  BOOST_TEST(nat.contact_length < 1.4);
  const auto& r = nat.long_contact;
  for (std::size_t i = 0; i < r.s.size(); ++i)
    if (r.s[i] > nat.contact_length + 1e-12) BOOST_TEST(r.sigma_n[i] >= -0.1);
  BOOST_CHECK_THROW(natural_contact_length(c, -1.0), cutbench::InputError);
}

BOOST_AUTO_TEST_CASE(frictional_chip_adaptive) {
  // Dissipation-driven refinement with the full contact model (Coulomb fixed point, top
  // streamline). α = 6°, μ = 0.2, φ_M, l = 1.5 t1 from n = 4 (144 elements): 2.2349, 2.2396,
  // 2.2228, 2.2211 (215 el.), then 2.2179, 2.2485, 2.2198 (398 el.): isotropic bisection converges
  // slowly and not monotonically toward Merchant (2.1945); uniform n = 8 gives 2.2000.
  CuttingSetup c = test::sliding_chip_at_merchant();
  std::vector<CuttingAdaptStep> hist;
  const auto r = adapt_cutting(c, 3, 0.5, &hist);
  for (const auto& h : hist) BOOST_TEST_MESSAGE("adaptive frictional chip: elements " << h.elements << " Fc_bar " << h.fc_bar);
  BOOST_TEST(hist.size() == 4u);
  BOOST_TEST(hist.back().elements > hist.front().elements);
  BOOST_TEST(std::abs(r.fc_bar / merchant_force_bar(c.phi, c.alpha, c.mu) - 1.0) < 0.015);
  BOOST_TEST(r.fc_bar < hist.front().fc_bar);
  BOOST_CHECK_THROW(adapt_cutting(c, -1), cutbench::InputError);
}

BOOST_AUTO_TEST_CASE(frictional_chip_against_merchant) {
  // Sliding single-shear-plane chip at φ = φ_M with the uncut top surface a streamline: the
  // rigid-block mechanism with Coulomb sliding (equilibrium of the chip, force at β from the rake
  // normal) gives Merchant's F̄c = cos(β − α)/(sin φ cos(φ + β − α)).
  // Measured: α = 0, μ = 0.1, l = 1.2: n = 4, 8, 12: 2.2441, 2.2124, 2.2063 (Merchant 2.2100);
  //           α = 6°, μ = 0.2, l = 1.5: 2.2349, 2.2000, 2.1927 (Merchant 2.1945).
  struct Case {
    double alpha_deg, mu, l;
  };
  for (const Case& k : {Case{0.0, 0.1, 1.2}, Case{6.0, 0.2, 1.5}}) {
    CuttingSetup c;
    c.alpha = k.alpha_deg * M_PI / 180;
    c.mu = k.mu;
    c.phi = merchant_shear_angle(c.alpha, c.mu);
    c.contact_length = k.l;
    c.n = 8;
    const auto r = solve_cutting(c);
    const double fm = merchant_force_bar(c.phi, c.alpha, c.mu);
    BOOST_TEST_MESSAGE("alpha=" << k.alpha_deg << " mu=" << k.mu << " Fc_bar=" << r.fc_bar << " (Merchant " << fm
                                << ") stick " << r.stick_fraction << " mu_sliding " << r.mu_sliding << " Coulomb steps "
                                << r.coulomb.iterations);
    BOOST_TEST(r.coulomb.converged);
    BOOST_TEST(std::abs(r.fc_bar / fm - 1.0) < 0.005);
    BOOST_TEST(r.stick_fraction < 0.05);
    BOOST_TEST(std::abs(r.mu_sliding - k.mu) < 1e-3);  // Coulomb bound active on the slip zone
    BOOST_TEST(r.solution.friction_dissipation > 0.05 * r.fc_bar);
  }
}

BOOST_AUTO_TEST_CASE(coulomb_fixed_point_anderson_matches_relaxed,
                     CUTBENCH_RELEASE_ONLY("paths covered by frictional_block_coulomb_fixed_point (plain update) and "
                                           "coulomb_fixed_point_slip_matches_pressure (Anderson)")) {
  // The pressure fixed point reaches the same non-associated Coulomb state with either update,
  // and Anderson acceleration takes fewer steps. Table 3 chip (t1 = 0.5 mm: mu = 0.4809,
  // phi = 30.4 deg, l = 1.899 t1, n = 6), both iterated to a change of 1e-5 of max p:
  {
    const LimitModel model = cutting_model(test::table3_chip_t1_05());
    CoulombOptions relaxed;
    relaxed.relaxation = 0.5;
    relaxed.tol = 1e-5;
    relaxed.max_iter = 80;
    CoulombOptions anderson = relaxed;
    anderson.relaxation = 1.0;
    anderson.anderson_depth = 5;
    CoulombReport ra, rr;
    const auto a = solve_limit_coulomb(model, {}, anderson, &ra);
    const auto r = solve_limit_coulomb(model, {}, relaxed, &rr);
    const Eigen::VectorXd pa = (-a.contact_rn).cwiseMax(0.0), pr = (-r.contact_rn).cwiseMax(0.0);
    const double dp = (pa - pr).cwiseAbs().maxCoeff() / pr.maxCoeff();
    BOOST_TEST_MESSAGE("Table 3 chip: Anderson " << ra.iterations << " steps, relaxed " << rr.iterations << ", collapse "
                                                 << a.collapse << " / " << r.collapse << ", max |dp|/max p " << dp);
    BOOST_TEST(ra.converged);
    BOOST_TEST(rr.converged);
    BOOST_TEST(ra.iterations < rr.iterations);
    BOOST_TEST(std::abs(a.collapse / r.collapse - 1.0) < 1e-6);
    BOOST_TEST(dp < 1e-3);
  }
  // restricted tool at mu = 1.5 (phi_M = 19.8 deg, l = t1/cos 6 deg), the default tolerance 1e-3:
  // measured 10 Anderson steps; the relaxed iteration needs about 45
  CuttingSetup c;
  c.alpha = 6.0 * M_PI / 180;
  c.mu = 1.5;
  c.phi = 19.845 * M_PI / 180;
  c.contact_length = 1.0 / std::cos(c.alpha);
  c.n = 6;
  const auto a = solve_cutting(c);
  BOOST_TEST_MESSAGE("restricted tool mu = 1.5: Anderson " << a.coulomb.iterations << " steps");
  BOOST_TEST(a.coulomb.converged);
  BOOST_TEST(a.coulomb.iterations <= 20);
}

BOOST_AUTO_TEST_CASE(coulomb_fixed_point_slip_matches_pressure) {
  // The fixed point on the slip (coupled cone, dilatancy cancelled by the previous step's normal
  // velocity) reaches the pressure iteration's state on the Table 3 chip (t1 = 0.5 mm, n = 6),
  // both iterated to a change of 1e-5, and takes fewer steps; at convergence the rake face does
  // not open where it carries load (w_n = 0 to the tolerance of the iterate).
  const LimitModel model = cutting_model(test::table3_chip_t1_05());
  CoulombOptions pressure;
  pressure.tol = 1e-5;
  pressure.max_iter = 80;
  pressure.anderson_depth = 5;
  CoulombOptions slip = pressure;
  slip.variable = CoulombVariable::slip;
  CoulombReport rp, rs;
  const auto p = solve_limit_coulomb(model, {}, pressure, &rp);
  const auto s = solve_limit_coulomb(model, {}, slip, &rs);
  const Eigen::VectorXd pp = (-p.contact_rn).cwiseMax(0.0), ps = (-s.contact_rn).cwiseMax(0.0);
  const double dp = (pp - ps).cwiseAbs().maxCoeff() / pp.maxCoeff();
  double wn_loaded = 0.0;
  for (Eigen::Index c = 0; c < s.contact_wn.size(); ++c)
    if (ps[c] > 1e-3 * ps.maxCoeff()) wn_loaded = std::max(wn_loaded, std::abs(s.contact_wn[c]));
  BOOST_TEST_MESSAGE("Table 3 chip: pressure " << rp.iterations << " steps, slip " << rs.iterations << ", collapse "
                                               << p.collapse << " / " << s.collapse << ", max |dp|/max p " << dp
                                               << ", max |w_n| where loaded " << wn_loaded << " (max |w_t| "
                                               << s.contact_wt.cwiseAbs().maxCoeff() << ")");
  BOOST_TEST(rp.converged);
  BOOST_TEST(rs.converged);
  BOOST_TEST(rs.iterations <= rp.iterations);
  BOOST_TEST(std::abs(s.collapse / p.collapse - 1.0) < 1e-5);
  BOOST_TEST(dp < 1e-3);
  BOOST_TEST(wn_loaded < 1e-4 * s.contact_wt.cwiseAbs().maxCoeff());
}

BOOST_AUTO_TEST_CASE(coulomb_fixed_point_started_from_its_solution) {
  // Started from its own converged iterate (the start a refined mesh gets from the previous one,
  // here on the same mesh: the rake-face profile interpolated back onto the contact nodes must
  // return the iterate to round-off), the fixed point on the slip stops within two steps with the same
  // collapse; a start of the wrong size is refused.
  CuttingSetup c = test::table3_chip_t1_05();
  const LimitModel model = cutting_model(c);
  CoulombOptions slip;
  slip.tol = 1e-5;
  slip.max_iter = 80;
  slip.anderson_depth = 5;
  slip.variable = CoulombVariable::slip;
  CuttingResult first;
  first.model = model;
  first.solution = solve_limit_coulomb(model, {}, slip, &first.coulomb);
  BOOST_REQUIRE(first.coulomb.converged);
  c.coulomb_start = coulomb_profile(first, c);
  BOOST_REQUIRE(c.coulomb_start.size() == model.contacts.size());
  const Eigen::VectorXd back = coulomb_start_on(model, c);
  BOOST_TEST((back - first.coulomb.iterate).cwiseAbs().maxCoeff() <= 1e-12 * first.coulomb.iterate.cwiseAbs().maxCoeff());
  CoulombOptions warm = slip;
  warm.start = back;
  CoulombReport rw;
  const auto again = solve_limit_coulomb(model, {}, warm, &rw);
  BOOST_TEST_MESSAGE("Table 3 chip: " << first.coulomb.iterations << " steps from the coupled solve, " << rw.iterations
                                      << " from the converged iterate; collapse " << first.solution.collapse << " / "
                                      << again.collapse);
  BOOST_TEST(rw.converged);
  BOOST_TEST(rw.iterations <= 2);
  BOOST_TEST(rw.iterations < first.coulomb.iterations);
  BOOST_TEST(std::abs(again.collapse / first.solution.collapse - 1.0) < 1e-5);
  warm.start = Eigen::VectorXd::Zero(back.size() + 1);
  BOOST_CHECK_THROW(solve_limit_coulomb(model, {}, warm), cutbench::InputError);
}

BOOST_AUTO_TEST_CASE(refined_mesh_starts_from_the_previous_slip_only) {
  // One refinement step of the Table 3 chip (n = 4): on the slip the refined mesh's fixed point starts from
  // the previous mesh's iterate (no coupled solve in its history) and reaches the cold start's
  // F_c bar to the fixed point's tolerance; on the pressure (a nodal reaction, which does not carry
  // over to another mesh) the warm start is not used and the run is the cold one exactly.
  CuttingSetup c = test::table3_chip_t1_05();
  c.n = 4;  // coarser than the chip's n = 6: the test runs under the sanitizers too
  AdaptOptions opt;
  opt.steps = 1;
  auto run = [&](bool on_slip, bool warm) {
    CuttingSetup s = c;
    s.coulomb_on_slip = on_slip;
    s.coulomb_warm_start = warm;
    return adapt_cutting(s, opt);
  };
  const auto pw = run(false, true), pc = run(false, false);
  BOOST_TEST(pw.fc_bar == pc.fc_bar);
  BOOST_TEST(pw.coulomb.collapse_history == pc.coulomb.collapse_history, boost::test_tools::per_element());
  const auto sw = run(true, true), sc = run(true, false);
  BOOST_TEST_MESSAGE("refined Table 3 chip on the slip: " << sw.coulomb.iterations << " steps warm, " << sc.coulomb.iterations
                                                          << " cold; F_c bar " << sw.fc_bar << " / " << sc.fc_bar);
  BOOST_TEST(sw.coulomb.converged);
  BOOST_TEST(sw.coulomb.collapse_history.size() == static_cast<std::size_t>(sw.coulomb.iterations));
  BOOST_TEST(sc.coulomb.collapse_history.size() == static_cast<std::size_t>(sc.coulomb.iterations) + 1);
  BOOST_TEST(std::abs(sw.fc_bar / sc.fc_bar - 1.0) < 1e-3);
}

BOOST_AUTO_TEST_CASE(tangent_loop_frictionless_keeps_merchant) {
  // Steady-state loop with φ* from the chip direction after the contact (η2, README 3.3):
  // without friction the straight chip leaves the contact along the rake face at φ_M
  // (|η2| < 1e-6 rad at n = 6 for α = 0 and 6°), so the loop keeps Merchant's angle after one
  // solve and F̄c is the single-shear-plane value.
  for (double alpha_deg : {0.0, 6.0}) {
    CuttingSetup c;
    c.alpha = alpha_deg * M_PI / 180;
    c.mu = 0.0;
    c.contact_length = 1.0 / std::cos(c.alpha);
    c.n = 6;
    const auto res = tangent_loop(c, [](const CuttingSetup& cs) { return solve_cutting(cs); });
    const double pm = merchant_shear_angle(c.alpha, 0.0);
    BOOST_TEST_MESSAGE("alpha=" << alpha_deg << " eta2(phi_M)=" << res.eta2.front() << " Fc_bar=" << res.final.fc_bar);
    BOOST_TEST(res.at_merchant);
    BOOST_TEST(res.phi.size() == 1u);
    BOOST_TEST(std::abs(res.phi_star - pm) < 1e-12);
    BOOST_TEST(std::abs(res.eta2.front()) < 1e-5);
    BOOST_TEST(std::abs(res.final.fc_bar / merchant_force_bar(pm, c.alpha, 0.0) - 1.0) < 0.03);
  }
}

BOOST_AUTO_TEST_CASE(chip_exit_angle_sign_with_friction) {
  // Table 2, t1 = 0.2 mm (α = 6°, μ = 0.6797, l = 2.5 t1), n = 6: at φ_M = 30.9° the free chip
  // curls away from the tool (η2 > 0), at 24° it turns into it (η2 < 0 by the flux through the
  // free rake line); the loop's φ* (26.9° at n = 6) lies between.
  CuttingSetup c;
  c.alpha = 6.0 * M_PI / 180;
  c.mu = 0.6797;
  c.contact_length = 2.5;
  c.n = 6;
  c.phi = merchant_shear_angle(c.alpha, c.mu);
  const auto hi = solve_cutting(c);
  c.phi = 24.0 * M_PI / 180;
  const auto lo = solve_cutting(c);
  BOOST_TEST_MESSAGE("eta2(phi_M)=" << hi.chip_exit_angle << " eta2(24 deg)=" << lo.chip_exit_angle
                                    << " flux_rake_free " << hi.flux_rake_free << ", " << lo.flux_rake_free);
  BOOST_TEST(hi.chip_exit_angle > 1e-3);
  BOOST_TEST(hi.flux_rake_free < 0.0);  // leaves the rake line beyond l (lifts off)
  BOOST_TEST(lo.chip_exit_angle < 1e-3);
  BOOST_TEST(lo.flux_rake_free > 0.0);  // would cross the rake face beyond l
}

// A frictional chip (alpha = 6 deg, mu = 0.5, phi_M, l = t1, n = 4) with the stream angles eta1, eta2.
static CuttingSetup turned_chip(double eta1, double eta2) {
  CuttingSetup c;
  c.n = 4;
  c.contact_length = 1.0;
  c.mu = 0.5;
  c.alpha = 6.0 * M_PI / 180;
  c.phi = merchant_shear_angle(c.alpha, c.mu);
  c.eta1 = eta1;
  c.eta2 = eta2;
  return c;
}

BOOST_AUTO_TEST_CASE(turned_free_chip_mass_balance) {
  // η2 ≠ 0 (paper Fig. 5): the chip beyond l is a second parallelogram turned about the line C–D;
  // the outward fluxes through the top,
  // the chip back (straight + turned), the chip end and the rake line beyond l add up to the
  // inflow t1 (incompressibility), which checks the classification of the turned surfaces.
  for (double eta2 : {-0.3, 0.2}) {
    const auto r = solve_cutting(turned_chip(0.0, eta2));
    const double total = r.flux_top + r.flux_back + r.flux_end + r.flux_rake_free;
    BOOST_TEST_MESSAGE("eta2=" << eta2 << " fluxes top " << r.flux_top << " back " << r.flux_back << " end " << r.flux_end
                                << " rake " << r.flux_rake_free << " sum " << total << " exit angle " << r.chip_exit_angle);
    BOOST_TEST(std::abs(total - 1.0) < 1e-6);
    BOOST_TEST(r.flux_end > 0.5);
  }
  CuttingSetup bad;
  bad.eta2 = 1.0;
  BOOST_CHECK_THROW(cutting_model(bad), cutbench::InputError);
}

BOOST_AUTO_TEST_CASE(stick_length_interpolates_the_threshold_crossing) {
  // A synthetic profile: slip 0 at the tip, 0.5e-3 at s = 0.2, 3e-3 at s = 0.4, 1 beyond; threshold
  // 1e-3 (v_chip = 1). Nodes with |w_t| < 1e-3: the first two, so the node count gives their
  // tributary share; the stick zone from the tip ends where the linear interpolation crosses 1e-3,
  // s = 0.2 + 0.2 (0.5e-3 / 2.5e-3) = 0.24 of the contact length 1.
  CuttingResult r;
  r.s = {0.0, 0.2, 0.4, 0.6, 0.8, 1.0};
  r.slip = {0.0, 0.5e-3, 3e-3, 1.0, 1.0, 1.0};
  r.sigma_n = std::vector<double>(6, -1.0);
  r.tau = std::vector<double>(6, 0.5);
  r.trib = {0.1, 0.2, 0.2, 0.2, 0.2, 0.1};
  r.v_chip = 1.0;
  r.stick_tol = 1e-3;
  contact_statistics(r, std::numeric_limits<double>::infinity());
  BOOST_TEST(std::abs(r.stick_fraction - 0.3) < 1e-12);
  BOOST_TEST(std::abs(r.stick_length_fraction - 0.24) < 1e-12);
  // truncated at l_max = 0.8: the same crossing over the shorter contact
  contact_statistics(r, 0.8);
  BOOST_TEST(std::abs(r.stick_length_fraction - 0.3) < 1e-12);
  // no crossing: the whole contact sticks; slipping at the tip: none
  r.slip = std::vector<double>(6, 0.0);
  contact_statistics(r, std::numeric_limits<double>::infinity());
  BOOST_TEST(r.stick_length_fraction == 1.0);
  r.slip = std::vector<double>(6, 0.5);
  contact_statistics(r, std::numeric_limits<double>::infinity());
  BOOST_TEST(r.stick_length_fraction == 0.0);
}

BOOST_AUTO_TEST_CASE(tau_plateau_ends_are_interpolated_level_crossings) {
  // |tau| of the field: 0.5, 0.95, 1.0 (maximum at s = 0.4), 0.92, 0.6, 0.5 at s = 0, 0.2, ..., 1.
  // Level 0.9: before the maximum the crossing lies between s = 0 and 0.2, at 0.2 (0.4 / 0.45) =
  // 0.17778; after it between s = 0.6 and 0.8, at 0.6 + 0.2 (0.02 / 0.32) = 0.6125.
  CuttingResult r;
  r.s = {0.0, 0.2, 0.4, 0.6, 0.8, 1.0};
  r.slip = std::vector<double>(6, 1.0);
  r.sigma_n = std::vector<double>(6, -1.0);
  r.tau = std::vector<double>(6, 0.5);
  r.tau_field = {-0.5, -0.95, -1.0, -0.92, -0.6, -0.5};
  r.trib = {0.1, 0.2, 0.2, 0.2, 0.2, 0.1};
  contact_statistics(r, std::numeric_limits<double>::infinity());
  BOOST_TEST(kTauPlateauLevel == 0.9);
  BOOST_TEST(std::abs(r.tau_plateau_start - 0.2 * 0.4 / 0.45) < 1e-12);
  BOOST_TEST(std::abs(r.tau_drop - 0.6125) < 1e-12);
  // truncated at l_max = 0.6: no fall below the level after the maximum, so the plateau runs to the
  // end of the contact
  contact_statistics(r, 0.6);
  BOOST_TEST(r.tau_drop == 1.0);
  BOOST_TEST(std::abs(r.tau_plateau_start - 0.2 * 0.4 / 0.45 / 0.6) < 1e-12);
}

BOOST_AUTO_TEST_CASE(chip_back_stream_angle_eta1) {
  // η1 (paper Fig. 5): the chip back over the contact runs from S to D1 = S + l (r − tan η1 n_r).
  // (1) The fluxes still add up to the inflow (the back over the contact, the turned free chip and
  // the chip end, now parallel to C–D1, are classified), and the back over the contact is
  // l / cos η1 long. (2) Frictionless, α = 0, φ = 45°, l = t1 the straight chip is the exact steady
  // state: a back turned away from the tool (η1 > 0) takes material in, one turned toward it gives
  // material out (measured at n = 6: flux over the back −0.152 / +0.144 at η1 = ±0.15), and the
  // fit of both stream angles returns from (0.15, 0.1) to the straight chip.
  for (const auto& [eta1, eta2] : {std::pair{0.2, -0.3}, std::pair{-0.1, 0.2}}) {
    const CuttingSetup c = turned_chip(eta1, eta2);
    const auto r = solve_cutting(c);
    const double total = r.flux_top + r.flux_back + r.flux_end + r.flux_rake_free;
    BOOST_TEST_MESSAGE("eta1=" << eta1 << " eta2=" << eta2 << " fluxes top " << r.flux_top << " back " << r.flux_back
                                << " (contact " << r.flux_back_contact << ") end " << r.flux_end << " rake " << r.flux_rake_free);
    BOOST_TEST(std::abs(total - 1.0) < 1e-6);
    BOOST_TEST(r.flux_end > 0.5);
    BOOST_TEST(std::abs(r.back_contact_length - c.contact_length / std::cos(eta1)) < 1e-12);
  }
  CuttingSetup c;
  c.n = 6;
  c.phi = M_PI / 4;
  c.contact_length = 1.0;
  c.eta1 = 0.15;
  const auto in = solve_cutting(c);
  c.eta1 = -0.15;
  const auto out = solve_cutting(c);
  BOOST_TEST(in.flux_back_contact < -0.1);
  BOOST_TEST(out.flux_back_contact > 0.1);
  c.eta1 = 0.15;
  c.eta2 = 0.1;
  const auto fit = fit_stream_angles(c, true, [](const CuttingSetup& cs) { return solve_cutting(cs); });
  for (std::size_t i = 0; i < fit.eta1.size(); ++i)
    BOOST_TEST_MESSAGE("fit " << i << ": eta1 " << fit.eta1[i] << " back angle " << fit.back_angle[i] << " eta2 " << fit.eta2[i]
                              << " exit angle " << fit.exit_angle[i]);
  BOOST_TEST(fit.converged);
  BOOST_TEST(std::abs(fit.eta1.back()) < 0.01);
  BOOST_TEST(std::abs(fit.eta2.back()) < 0.01);
  // a back thinner than 0.1 t2 at l and a held chip back are refused
  CuttingSetup bad;
  bad.eta1 = -0.7;
  bad.contact_length = 3.0;
  BOOST_CHECK_THROW(cutting_model(bad), cutbench::InputError);
  bad.eta1 = 0.1;
  bad.streamline = 2;
  BOOST_CHECK_THROW(cutting_model(bad), cutbench::InputError);
}

BOOST_AUTO_TEST_CASE(curled_free_chip) {
  // The curl of the free chip beyond l (CuttingSetup::curl, our extension of Fig. 5): the chip swept
  // by C-D1 turning rigidly about one centre. (1) The fluxes of the curled chip still add up to the
  // inflow (its arcs and its turned end are classified). (2) Frictionless, alpha = 0, phi = 45 deg,
  // l = t1, the straight chip is the exact steady state: with eta2 = 0 and a curl the free chip
  // starts along the flow (start angle near 0) and its end is turned by the curl against the
  // straight-moving material (exit angle about -curl); the fit of eta2 and the curl returns to the
  // straight chip. (3) A curl that puts its centre inside the chip is refused.
  for (double curl : {-0.6, 0.4}) {
    CuttingSetup c = turned_chip(0.0, -0.1);
    c.curl = curl;
    const auto r = solve_cutting(c);
    const double total = r.flux_top + r.flux_back + r.flux_end + r.flux_rake_free;
    BOOST_TEST_MESSAGE("curl=" << curl << " fluxes top " << r.flux_top << " back " << r.flux_back << " (free " << r.flux_back_free
                               << ") end " << r.flux_end << " rake " << r.flux_rake_free << " (free " << r.flux_tool_free
                               << ") total " << total << " face length " << r.free_face_length);
    BOOST_TEST(std::abs(total - 1.0) < 1e-6);
    BOOST_TEST(r.free_face_length > 0.7 * c.chip_extra * r.t2);  // the mean of the two arcs (the inner one shorter)
    BOOST_TEST(r.free_face_length < 1.3 * c.chip_extra * r.t2);
  }
  CuttingSetup c;
  c.n = 6;
  c.phi = M_PI / 4;
  c.contact_length = 1.0;
  for (double curl : {0.3, -0.3}) {
    c.curl = curl;
    const auto r = solve_cutting(c);
    BOOST_TEST_MESSAGE("curl " << curl << ": start angle " << r.chip_start_angle << ", exit angle " << r.chip_exit_angle);
    BOOST_TEST(std::abs(r.chip_start_angle) < 0.1);
    BOOST_TEST(std::abs(r.chip_exit_angle + curl) < 0.1);
  }
  c.curl = 0.3;
  c.eta2 = 0.1;
  const auto fit = fit_stream_angles(c, false, [](const CuttingSetup& cs) { return solve_cutting(cs); }, 10,
                                     0.25 * M_PI / 180, true);
  for (std::size_t i = 0; i < fit.curl.size(); ++i)
    BOOST_TEST_MESSAGE("fit " << i << ": eta2 " << fit.eta2[i] << " start angle " << fit.start_angle[i] << " curl " << fit.curl[i]
                              << " exit angle " << fit.exit_angle[i]);
  BOOST_TEST(fit.converged);
  BOOST_TEST(std::abs(fit.eta2.back()) < 0.01);
  BOOST_TEST(std::abs(fit.curl.back()) < 0.01);
  c.curl = 0.95 * c.chip_extra * chip_thickness(c.t1, c.phi, c.alpha) / (c.t1 * 0.5);
  BOOST_CHECK_THROW(cutting_model(c), cutbench::InputError);
}

BOOST_AUTO_TEST_CASE(workpiece_block_frictionless_converges_to_merchant,
                     CUTBENCH_RELEASE_ONLY("paths covered by workpiece_block_depth_does_not_matter and "
                                           "frictional_chip_adaptive")) {
  // The paper's domain: the workpiece below the cutting line is meshed and the tool tip is a rake
  // contact node. Frictionless, alpha = 0, phi = 45 deg, l = t1: the single-shear-plane mechanism
  // (the block moving rigidly, touching the chip at the tip only) gives Merchant's F_c bar = 2
  // exactly, so the discrete collapse power must approach 2 from above as the mesh is refined at
  // the tip (measured: 2.622 on the uniform n = 4 mesh, 2.022 after 12 Doerfler steps, 1604
  // elements; uniform n = 16: 2.153), and all the inflow of the layer must come out of the chip.
  CuttingSetup c;
  c.streamline = 0;
  c.phi = M_PI / 4;
  c.contact_length = 1.0;
  c.depth = 2.0;
  c.n = 4;
  std::vector<CuttingAdaptStep> hist;
  AdaptOptions opt;
  opt.steps = 12;
  opt.fraction = 0.5;
  const auto r = adapt_cutting(c, opt, &hist);
  for (const auto& h : hist) BOOST_TEST_MESSAGE("elements " << h.elements << " Fc_bar " << h.fc_bar);
  for (const auto& h : hist) BOOST_TEST(h.fc_bar > 2.0 * (1.0 - 1e-3));
  BOOST_TEST(hist.back().fc_bar < hist.front().fc_bar - 0.4);
  BOOST_TEST(r.fc_bar < 2.0 * 1.02);
  const double total = r.flux_top + r.flux_back + r.flux_end + r.flux_rake_free + r.flux_under;
  BOOST_TEST(std::abs(total - 1.0) < 1e-6);  // incompressibility with the block's inflow and outflow
  BOOST_TEST(std::abs(r.flux_under) < 0.01);
  BOOST_TEST(r.flux_end > 0.98);
  // the tip is an ordinary rake contact node (s = 0), not a fixed node
  BOOST_TEST(r.s.front() == 0.0);
}

BOOST_AUTO_TEST_CASE(workpiece_block_depth_does_not_matter) {
  // Table 2 conditions (alpha = 6 deg, mu = 0.4809, phi = 30.4 deg, l = 1.899 t1, n = 6): the
  // block stays rigid below the first cell rows, so depth and exit length do not change the
  // solution (measured: F_c bar 3.34471 for depth 0.5-8 and exit length 1-4)
  CuttingSetup c = test::table3_chip_t1_05();
  c.depth = 1.0;
  const auto a = solve_cutting(c);
  c.depth = 4.0;
  c.exit_length = 4.0;
  const auto b = solve_cutting(c);
  BOOST_TEST_MESSAGE("depth 1: " << a.fc_bar << " depth 4: " << b.fc_bar << " layer model (depth 0) differs");
  BOOST_TEST(std::abs(a.fc_bar - b.fc_bar) < 1e-4 * a.fc_bar);
  BOOST_TEST(std::abs(a.ff_bar - b.ff_bar) < 1e-3 * std::abs(a.ff_bar));
  CuttingSetup bad = c;
  bad.depth = 0.1;
  BOOST_CHECK_THROW(cutting_model(bad), cutbench::InputError);
  bad.depth = 2.0;
  bad.exit_length = 0.2;
  BOOST_CHECK_THROW(cutting_model(bad), cutbench::InputError);
}

// The loop's control flow with a stub solve (no mechanics): eta2 = phi - phi0, so phi* = phi0 to
// within tol_phi below it; no sign change above phi_min gives the smallest angle tried, not
// converged; a phi_min above phi_M - step keeps the phi_M solve as the result.
// The turning-point loop's control flow with stubs: phi* below phi_M is taken and kept once it
// repeats; phi* above phi_M keeps phi_M after one solve; a phi* that keeps moving stops after the
// fourth update; restart runs before every new phi.
BOOST_AUTO_TEST_CASE(turning_point_loop_updates_and_stops) {
  const double deg = 3.14159265358979323846 / 180.0;
  CuttingSetup c;
  c.alpha = 0.0;
  c.mu = 0.5;
  const double phi_m = merchant_shear_angle(c.alpha, c.mu);
  c.phi = phi_m;
  auto solve = [](CuttingSetup& cs) {
    CuttingResult r;
    r.fc_bar = 1.0 + cs.phi;
    return r;
  };
  int restarts = 0;
  auto restart = [&](CuttingSetup&) { ++restarts; };
  auto res = turning_point_loop(c, solve, [&](const CuttingSetup&, const CuttingResult&) { return 26.0 * deg; }, restart);
  BOOST_TEST(res.phi.size() == 2u);
  BOOST_TEST(res.phi.front() == phi_m);
  BOOST_TEST(c.phi == 26.0 * deg);
  BOOST_TEST(res.final.fc_bar == 1.0 + 26.0 * deg);
  BOOST_TEST(restarts == 1);
  c.phi = phi_m;
  res = turning_point_loop(c, solve, [&](const CuttingSetup&, const CuttingResult&) { return 40.0 * deg; }, restart);
  BOOST_TEST(res.phi.size() == 1u);
  BOOST_TEST(c.phi == phi_m);
  c.phi = phi_m;
  double next = 28.0 * deg;  // moves by 1 deg at every solve
  res = turning_point_loop(c, solve, [&](const CuttingSetup&, const CuttingResult&) { return next -= 1.0 * deg; }, restart);
  BOOST_TEST(res.phi.size() == 5u);  // the first solve and four updates
}

BOOST_AUTO_TEST_CASE(tangent_loop_bracket_bisection_and_no_bracket) {
  const double deg = 3.14159265358979323846 / 180.0;
  CuttingSetup c;
  c.alpha = 0.0;
  c.mu = 0.5;
  const double phi_m = merchant_shear_angle(c.alpha, c.mu);  // 31.72 deg
  int calls = 0;
  auto stub = [&](double phi0) {
    return [&calls, phi0](const CuttingSetup& cs) {
      ++calls;
      CuttingResult r;
      r.chip_exit_angle = cs.phi - phi0;
      r.fc_bar = 1.0 + cs.phi;  // marks which solve was kept
      return r;
    };
  };
  TangentLoopOptions opt;
  auto res = tangent_loop(c, stub(26.6 * deg), opt);
  BOOST_TEST(res.converged);
  BOOST_TEST(!res.at_merchant);
  BOOST_TEST(res.phi_star <= 26.6 * deg + 1e-12);
  BOOST_TEST(res.phi_star > 26.6 * deg - opt.tol_phi);
  BOOST_TEST(res.final.fc_bar == 1.0 + res.phi_star);
  BOOST_TEST(res.phi.size() == static_cast<std::size_t>(calls));
  // phi0 above phi_M: phi_M kept after one solve
  calls = 0;
  res = tangent_loop(c, stub(40.0 * deg), opt);
  BOOST_TEST(res.at_merchant);
  BOOST_TEST(calls == 1);
  BOOST_TEST(res.phi_star == phi_m);
  // no sign change above phi_min: smallest angle tried, not converged, a real result kept
  res = tangent_loop(c, stub(5.0 * deg), opt);
  BOOST_TEST(!res.converged);
  BOOST_TEST(res.phi_star >= opt.phi_min);
  BOOST_TEST(res.phi_star < opt.phi_min + opt.step);
  BOOST_TEST(res.final.fc_bar == 1.0 + res.phi_star);
  // phi_min too close to phi_M for one step down: the phi_M solve is the result
  opt.phi_min = phi_m - 1.0 * deg;
  res = tangent_loop(c, stub(5.0 * deg), opt);
  BOOST_TEST(!res.converged);
  BOOST_TEST(res.phi_star == phi_m);
  BOOST_TEST(res.final.fc_bar == 1.0 + phi_m);
  // a Merchant angle outside (phi_min, 90 deg) is an input error
  opt.phi_min = 40.0 * deg;
  BOOST_CHECK_THROW(tangent_loop(c, stub(5.0 * deg), opt), cutbench::InputError);
}

BOOST_AUTO_TEST_SUITE_END()
