#include "cutbench/common/model.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "cutbench/common/errors.hpp"

namespace cutbench {

ParamSpec param(std::string name, Dim dim, std::string description) {
  ParamSpec p;
  p.name = std::move(name);
  p.dim = dim;
  p.description = std::move(description);
  return p;
}

ParamSpec param(std::string name, Dim dim, std::string description, std::optional<double> default_value,
                double min, double max, bool min_inclusive, bool max_inclusive) {
  ParamSpec p = param(std::move(name), dim, std::move(description));
  p.default_value = default_value;
  p.min = min;
  p.max = max;
  p.min_inclusive = min_inclusive;
  p.max_inclusive = max_inclusive;
  return p;
}

ParamSpec integer_param(std::string name, std::string description, std::optional<double> default_value, double min,
                        double max) {
  ParamSpec p = param(std::move(name), Dim::dimensionless, std::move(description), default_value, min, max);
  p.kind = ParamKind::integer;
  return p;
}

ParamSpec switch_param(std::string name, std::string description, bool default_value) {
  ParamSpec p = param(std::move(name), Dim::dimensionless, std::move(description), default_value ? 1.0 : 0.0, 0.0, 1.0);
  p.kind = ParamKind::boolean;
  return p;
}

ParamSpec option_param(std::string name, std::string description, std::vector<ParamOption> options,
                       const std::string& default_option) {
  ParamSpec p = param(std::move(name), Dim::dimensionless, std::move(description));
  p.kind = ParamKind::option;
  p.options = std::move(options);
  p.min = 0.0;
  p.max = static_cast<double>(p.options.size()) - 1.0;
  p.default_value = option_index(p, default_option, p.name);
  return p;
}

std::string kind_name(ParamKind kind) {
  switch (kind) {
    case ParamKind::real: return "real";
    case ParamKind::integer: return "integer";
    case ParamKind::boolean: return "switch";
    case ParamKind::option: return "option";
  }
  return "real";
}

namespace {
std::string option_list(const ParamSpec& p) {
  std::string s;
  for (const auto& o : p.options) s += (s.empty() ? "\"" : ", \"") + o.name + "\"";
  return s;
}
}  // namespace

int option_index(const ParamSpec& p, const std::string& text, const std::string& field) {
  for (std::size_t i = 0; i < p.options.size(); ++i) {
    if (p.options[i].name == text) return static_cast<int>(i);
  }
  throw InputError(field, "one of " + option_list(p) + " (got \"" + text + "\")");
}

std::string format_param_value(const ParamSpec& p, double value) {
  if (p.kind == ParamKind::option) {
    const auto i = static_cast<std::size_t>(value);
    if (value >= 0.0 && i < p.options.size() && static_cast<double>(i) == value) return p.options[i].name;
  }
  if (p.kind == ParamKind::boolean && (value == 0.0 || value == 1.0)) return value == 1.0 ? "true" : "false";
  if (std::isnan(value)) return "unset";
  std::ostringstream os;
  os.precision(p.kind == ParamKind::integer ? 15 : 6);
  os << value;
  return os.str();
}

double parse_param_value(const ParamSpec& p, const std::string& text, const std::string& field) {
  switch (p.kind) {
    case ParamKind::option: return option_index(p, text, field);
    case ParamKind::boolean:
      if (text == "true") return 1.0;
      if (text == "false") return 0.0;
      throw InputError(field, "a switch: true or false (got \"" + text + "\")");
    default: return parse_quantity(text, p.dim, field);
  }
}

std::string describe_range(const ParamSpec& p) {
  if (p.kind == ParamKind::option) return "one of " + option_list(p);
  if (p.kind == ParamKind::boolean) return "true or false";
  std::ostringstream os;
  os.precision(6);
  const std::string unit = si_unit(p.dim);
  auto show = [&](double v) {
    if (p.dim == Dim::angle) {
      os << v * 180.0 / 3.14159265358979323846 << " deg";
    } else {
      os << v << (unit == "1" ? "" : " " + unit);
    }
  };
  const bool has_min = std::isfinite(p.min), has_max = std::isfinite(p.max);
  if (has_min && has_max) {
    os << (p.min_inclusive ? "[" : "(");
    show(p.min);
    os << ", ";
    show(p.max);
    os << (p.max_inclusive ? "]" : ")");
  } else if (has_min) {
    os << (p.min_inclusive ? ">= " : "> ");
    show(p.min);
  } else if (has_max) {
    os << (p.max_inclusive ? "<= " : "< ");
    show(p.max);
  } else {
    os << "any finite value";
  }
  return os.str();
}

Values validate_params(const ModelSpec& spec, const Values& given) {
  Values out;
  for (const auto& [name, value] : given) {
    auto it = std::find_if(spec.params.begin(), spec.params.end(),
                           [&name = name](const ParamSpec& p) { return p.name == name; });
    if (it == spec.params.end()) {
      std::string known;
      for (const auto& p : spec.params) known += (known.empty() ? "" : ", ") + p.name;
      throw InputError(name, "unknown parameter of model '" + spec.name + "' (known: " + known + ")");
    }
  }
  for (const auto& p : spec.params) {
    auto it = given.find(p.name);
    double v;
    if (it != given.end()) {
      v = it->second;
    } else if (p.default_value) {
      out[p.name] = *p.default_value;
      continue;
    } else {
      throw InputError(p.name, "missing required parameter of model '" + spec.name + "' (" +
                                   p.description + ", " + describe_range(p) + ")");
    }
    if (!std::isfinite(v)) throw InputError(p.name, "must be finite");
    if (p.kind != ParamKind::real && v != std::round(v)) {
      throw InputError(p.name, std::string(p.kind == ParamKind::integer ? "a whole number"
                                           : p.kind == ParamKind::option ? "an option index" : "a switch") +
                                   " (got " + format_param_value(p, v) + "); expected " + describe_range(p));
    }
    const bool below = p.min_inclusive ? v < p.min : v <= p.min;
    const bool above = p.max_inclusive ? v > p.max : v >= p.max;
    if (below || above) {
      std::ostringstream os;
      os.precision(6);
      if (p.dim == Dim::angle) {
        os << v * 180.0 / 3.14159265358979323846 << " deg";
      } else {
        os << v << (si_unit(p.dim) == "1" ? "" : " " + si_unit(p.dim));
      }
      throw InputError(p.name, "value " + os.str() + " out of range; expected " + describe_range(p));
    }
    out[p.name] = v;
  }
  return out;
}

ModelRegistry& ModelRegistry::instance() {
  static ModelRegistry registry;
  return registry;
}

void ModelRegistry::add(ModelSpec spec) {
  if (find(spec.name)) throw std::logic_error("model registered twice: " + spec.name);
  models_.push_back(std::move(spec));
}

const ModelSpec* ModelRegistry::find(const std::string& name) const {
  for (const auto& m : models_) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

const ModelSpec& ModelRegistry::get(const std::string& name) const {
  if (const auto* m = find(name)) return *m;
  throw InputError("model", "unknown model '" + name + "' (see `cutbench eval --list`)");
}

ModelResult evaluate_model(const ModelSpec& spec, const Values& given) {
  Values params = validate_params(spec, given);
  ModelResult r = spec.evaluate(params);
  if (!r.applicable) {
    for (const auto& o : spec.outputs) {
      if (!r.outputs.count(o.name)) r.outputs[o.name] = nan_value();
    }
  }
  return r;
}

}  // namespace cutbench
