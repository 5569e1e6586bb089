#pragma once
// One name per shared physical quantity, for every analytical model and solver and so for every
// case file. The papers use their own symbols (listed); a parameter that stands for one of these
// quantities carries the glossary name, whatever the paper calls it.
#include <map>
#include <string>

namespace cutbench::glossary {

// rake angle: alpha (Nairn, Figueiredo, Kahwash), gamma (Afrasiabi), lambda (Aghababaei) [rad]
inline constexpr const char* kRakeAngle = "rake";
// clearance angle of the tool's flank face [rad]
inline constexpr const char* kClearanceAngle = "clearance";
// Coulomb friction coefficient on the rake face: mu (all papers) [1]
inline constexpr const char* kFriction = "mu";
// depth of cut = uncut chip thickness: h (Nairn), t1 (Figueiredo), t_u (Afrasiabi), d
// (Aghababaei), "depth of cut" (Kahwash) [m]
inline constexpr const char* kDepthOfCut = "t1";
// cutting speed: V (Nairn), v_c (Afrasiabi, Kahwash) [m/s]
inline constexpr const char* kCuttingSpeed = "speed";
// width of cut (plane-strain models report forces per unit width instead) [m]
inline constexpr const char* kWidthOfCut = "w";

// Names that parameters for these quantities had before the glossary: a case file that uses one
// is told the glossary name (old name -> glossary name).
inline const std::map<std::string, std::string>& retired_names() {
  static const std::map<std::string, std::string> names = {
      {"h", kDepthOfCut},        {"d", kDepthOfCut},   {"depth", kDepthOfCut},
      {"uncut_thickness", kDepthOfCut}, {"alpha", kRakeAngle}, {"friction", kFriction}};
  return names;
}

}  // namespace cutbench::glossary
