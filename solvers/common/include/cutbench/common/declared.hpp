#pragma once
// Parameters declared once: each entry is the parameter's declaration (name, kind, dimension,
// default, admissible range or named options: ParamSpec) together with where its value goes in
// the solver's setup struct. The declaration gives the validation, `cutbench describe`, the
// case-file vocabulary and the run-cache key (all from the ParamSpec list); make() gives the copy
// into the struct. So a parameter is written in one place, not three (spec, field, copy line).
//
//   DeclaredParams<CuttingSetup> d;
//   d.bind(param(glossary::kDepthOfCut, Dim::length, "depth of cut h", 0.9e-3, 0.0, kInf, false), &CuttingSetup::h);
//   d.bind(integer_param("snapshots", "...", 4, 0, 1000), &CuttingSetup::snapshots);
//   d.add(param("K", Dim::stress, "bulk modulus", ...), [](CuttingSetup& s, double v) { s.material.K = v; });
//   const CuttingSetup s = d.make(validate_params(spec, given));
#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "cutbench/common/model.hpp"

namespace cutbench {

template <class Setup>
class DeclaredParams {
public:
  using Setter = std::function<void(Setup&, double)>;

  // A parameter with its own conversion (nested members, derived fields).
  DeclaredParams& add(ParamSpec spec, Setter set) {
    specs_.push_back(std::move(spec));
    setters_.push_back(std::move(set));
    return *this;
  }
  // A parameter copied into a member: double (SI), int (integer), bool (switch) or an enum
  // (option: the option's index is the enumerator's value).
  template <class T>
  DeclaredParams& bind(ParamSpec spec, T Setup::*member) {
    return add(std::move(spec), [member](Setup& s, double v) {
      if constexpr (std::is_same_v<T, bool>) {
        s.*member = v != 0.0;
      } else if constexpr (std::is_enum_v<T> || std::is_integral_v<T>) {
        s.*member = static_cast<T>(static_cast<long long>(v));
      } else {
        s.*member = static_cast<T>(v);
      }
    });
  }
  // A parameter that only the runner reads from Values (no member).
  DeclaredParams& declare(ParamSpec spec) { return add(std::move(spec), nullptr); }

  const std::vector<ParamSpec>& specs() const { return specs_; }

  // The setup from validated Values (every declared parameter present), starting from `base`.
  Setup make(const Values& v, Setup base = Setup{}) const {
    for (std::size_t k = 0; k < specs_.size(); ++k) {
      if (setters_[k]) setters_[k](base, v.at(specs_[k].name));
    }
    return base;
  }

private:
  std::vector<ParamSpec> specs_;
  std::vector<Setter> setters_;
};

}  // namespace cutbench
