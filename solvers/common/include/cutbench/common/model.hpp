#pragma once
// An evaluable model: named parameters with dimension, default and admissible range; named
// outputs with SI units; a pure evaluation function. Analytical models register themselves as
// ModelSpecs; `cutbench eval` and analytic case series evaluate them by name.
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cutbench/common/units.hpp"

namespace cutbench {

using Values = std::map<std::string, double>;

// What kind of value a parameter takes. Every kind is carried as a double in Values (SI for real
// parameters; the whole number; 0/1 for a switch; the option's index for an option), so the
// solvers, the run-cache key and the result files see one representation; the declaration says
// how a case file writes it: a number or "value unit" (real, integer), true/false (switch), one
// of the option names (option).
enum class ParamKind { real, integer, boolean, option };

struct ParamOption {
  std::string name;         // what a case file writes, e.g. "musl"
  std::string description;  // one line for `cutbench describe`
};

struct ParamSpec {
  std::string name;
  Dim dim = Dim::dimensionless;
  std::string description;
  std::optional<double> default_value;  // SI; absent = required. NaN default = optional, unset.
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_inclusive = true;
  bool max_inclusive = true;
  ParamKind kind = ParamKind::real;
  std::vector<ParamOption> options;  // option: the value is the index into this list
};

struct OutputSpec {
  std::string name;
  Dim dim = Dim::dimensionless;
  std::string description;
};

// Result of one evaluation. `applicable == false` means the model has no solution for these
// inputs (the paper says it does not apply); outputs are then NaN and `note` says why.
struct ModelResult {
  Values outputs;
  bool applicable = true;
  std::string note;
};

struct ModelSpec {
  std::string name;
  std::string description;
  std::string source;  // paper and equation numbers
  std::vector<ParamSpec> params;
  std::vector<OutputSpec> outputs;
  std::function<ModelResult(const Values&)> evaluate;
};

// Range helpers for ParamSpec definitions.
ParamSpec param(std::string name, Dim dim, std::string description);
// A parameter with its default and admissible range in one call. default_value: SI; NaN = optional
// and unset; std::nullopt = required.
ParamSpec param(std::string name, Dim dim, std::string description, std::optional<double> default_value,
                double min, double max, bool min_inclusive = true, bool max_inclusive = true);
// A count or an order: a whole number in [min, max].
ParamSpec integer_param(std::string name, std::string description, std::optional<double> default_value, double min,
                        double max);
// A switch: true or false in a case file, 1 or 0 in Values.
ParamSpec switch_param(std::string name, std::string description, bool default_value);
// An enumeration: one of the named options in a case file, the option's index in Values.
ParamSpec option_param(std::string name, std::string description, std::vector<ParamOption> options,
                       const std::string& default_option);
// The index of option `text` of p (InputError naming `field` and the options otherwise).
int option_index(const ParamSpec& p, const std::string& text, const std::string& field);
// A parameter value as a case file writes it: the option name, true/false, or the number (SI).
std::string format_param_value(const ParamSpec& p, double value);
// A value from the command line or a case-file string: an option name, true/false, or a
// quantity "value unit" of p's dimension. InputError naming `field` otherwise.
double parse_param_value(const ParamSpec& p, const std::string& text, const std::string& field);
std::string kind_name(ParamKind kind);

// Check names, fill defaults, check ranges. Throws InputError naming the field and the range.
Values validate_params(const ModelSpec& spec, const Values& given);
std::string describe_range(const ParamSpec& p);

// Registry of all evaluable models (filled by the libraries at static-init-free call time).
class ModelRegistry {
public:
  static ModelRegistry& instance();
  void add(ModelSpec spec);
  const ModelSpec* find(const std::string& name) const;
  const ModelSpec& get(const std::string& name) const;  // throws InputError("model", ...)
  const std::vector<ModelSpec>& all() const { return models_; }

private:
  std::vector<ModelSpec> models_;
};

// Evaluate with validation; NaN-fills outputs when not applicable.
ModelResult evaluate_model(const ModelSpec& spec, const Values& given);

constexpr double nan_value() { return std::numeric_limits<double>::quiet_NaN(); }

}  // namespace cutbench
