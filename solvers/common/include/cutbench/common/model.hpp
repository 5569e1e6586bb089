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

struct ParamSpec {
  std::string name;
  Dim dim = Dim::dimensionless;
  std::string description;
  std::optional<double> default_value;  // SI; absent = required. NaN default = optional, unset.
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_inclusive = true;
  bool max_inclusive = true;
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
ParamSpec& positive(ParamSpec& p);
ParamSpec& non_negative(ParamSpec& p);
// A parameter that selects an option or counts something: its value must be a whole number
// (InputError naming the parameter otherwise, e.g. criterion = 1.4).
int whole_number(const Values& v, const std::string& name);

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
