#pragma once
// Error types shared by every component. InputError is bad user input (case files, parameters,
// command line): the CLI reports its message and exits with code 2, having written nothing.
#include <stdexcept>
#include <string>

namespace cutbench {

class InputError : public std::runtime_error {
public:
  InputError(std::string field, const std::string& message)
      : std::runtime_error(field.empty() ? message : field + ": " + message), field_(std::move(field)) {}
  const std::string& field() const noexcept { return field_; }

private:
  std::string field_;
};

// A numerical failure inside a model or solver (no convergence, singular system).
class NumericalError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

}  // namespace cutbench
