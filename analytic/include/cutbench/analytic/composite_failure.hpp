#pragma once
// Plane-stress failure criteria of a unidirectional lamina as summarised in Kahwash, Shyha,
// Maheri (2018), Compos. Struct. 198:156-173, Appendix A (maximum stress, Hashin, LaRC02), with
// the LaRC02/LaRC03 auxiliary relations of EQUATIONS.md E1 and Hashin of E2. Stresses in the
// material frame (1 = fibre), SI units (Pa), angles in radians. Pure functions.
//
// Each criterion returns per-mode failure indices (failure at 1):
//   fibre  : tension or compression (kinking for LaRC02) index,
//   matrix : tension or compression index,
//   shear  : in-plane shear index (maximum stress only; NaN elsewhere).
// Choices (see analytic/README.md): maximum stress in the paper's squared form; UD bulk
// workpiece, so no in-situ strength enhancement (Y_T^is = Y_T, S_L^is = S_L).
#include <string>

#include "cutbench/common/model.hpp"

namespace cutbench::analytic {

struct Lamina {
  double X_T = 0.0, X_C = 0.0;  // fibre-direction strengths (both positive)
  double Y_T = 0.0, Y_C = 0.0;  // transverse strengths (both positive)
  double S_L = 0.0;             // in-plane (longitudinal) shear strength
  double S_T = 0.0;             // transverse shear strength; <= 0 or NaN: Y_C cos a0 (sin a0 + cos a0/tan 2a0)
  // LaRC02 only:
  double E1 = 0.0;              // fibre-direction modulus
  double G12 = 0.0;             // in-plane shear modulus
  double nu12 = 0.0;            // major Poisson ratio (eps11 = (s11 - nu12 s22)/E1)
  double eps1_T = 0.0;          // fibre tensile failure strain; <= 0 or NaN: X_T/E1
  double alpha0 = 0.9250245035569946;  // fracture angle in pure transverse compression (53 deg)
  double g = 1.0;               // G_Ic/G_IIc in the matrix-tension form (1: Kahwash's printed form)
};

struct PlaneStress {
  double s11 = 0.0, s22 = 0.0, t12 = 0.0;
};

// Mode codes of the governing (largest) index.
enum class FailureMode : int {
  fibre_tension = 1,
  fibre_compression = 2,
  matrix_tension = 3,
  matrix_compression = 4,
  shear = 5,
};

struct FailureIndices {
  double fibre = 0.0;
  double matrix = 0.0;
  double shear = 0.0;            // NaN when the criterion has no separate shear mode
  double index = 0.0;            // max of the defined indices
  FailureMode mode = FailureMode::matrix_tension;
  double fracture_angle = 0.0;   // LaRC02 matrix compression: maximising fracture-plane angle
  double misalignment = 0.0;     // LaRC02 fibre compression: misalignment angle psi
};

enum class Criterion : int { max_stress = 0, hashin = 1, larc02 = 2 };
enum class EnvelopePlane : int { s11_s22 = 0, s22_t12 = 1 };

// The case-file declaration of the criterion: options "max_stress", "hashin", "larc02" in the
// order of Criterion (the value is the enumerator).
ParamSpec criterion_param(const std::string& default_option);

// S_T default used by Hashin and LaRC02: Y_C cos a0 (sin a0 + cos a0/tan(2 a0)).
double transverse_shear_strength(double Y_C, double alpha0);
// LaRC friction-like coefficients eta_T = -1/tan(2 a0), eta_L = -S_L cos(2 a0)/(Y_C cos^2 a0).
double larc_eta_T(double alpha0);
double larc_eta_L(double S_L, double Y_C, double alpha0);
// Misalignment angle at pure axial compression failure, psi_C (Kahwash A.3).
double larc_misalignment_angle_at_XC(double S_L, double X_C, double eta_L);
// g = G_Ic/G_IIc estimated as (Lambda22/Lambda44)(Y_T/S_L)^2 with Lambda22 = 2(1/E2 - nu21^2/E1),
// Lambda44 = 1/G12 (Davila et al.): an alternative to the printed g = 1 form.
double larc_toughness_ratio(double E1, double E2, double nu21, double G12, double Y_T, double S_L);

FailureIndices max_stress_failure(const PlaneStress& s, const Lamina& m);
FailureIndices hashin_failure(const PlaneStress& s, const Lamina& m);
FailureIndices larc02_failure(const PlaneStress& s, const Lamina& m);
// As above; with `matrix_compression_search` false the fracture-plane search of matrix
// compression (the costly part: 180-point scan and golden-section refinement) is skipped and the
// compressive matrix index is returned as NaN (for callers that need only the fibre index or
// know the matrix index to be below 1). Every other index is identical.
FailureIndices larc02_failure(const PlaneStress& s, const Lamina& m, bool matrix_compression_search);
FailureIndices failure_indices(Criterion c, const PlaneStress& s, const Lamina& m);

struct EnvelopePoint {
  double radius = 0.0;  // distance from the fixed-stress origin to the failure surface [Pa]
  double s1 = 0.0;      // sigma11 (plane 0) or sigma22 (plane 1) at failure
  double s2 = 0.0;      // sigma22 (plane 0) or tau12 (plane 1) at failure
};

// First crossing of index = 1 along the ray (cos theta, sin theta) in the chosen plane, with the
// third stress held at `fixed` (tau12 for plane 0, sigma11 for plane 1). Geometric bracket scan
// (2 % steps) then GSL Brent. Throws NumericalError when the ray never fails or the fixed
// stress alone already fails the lamina.
EnvelopePoint failure_envelope_point(Criterion c, EnvelopePlane plane, double theta, double fixed,
                                     const Lamina& m);

}  // namespace cutbench::analytic
