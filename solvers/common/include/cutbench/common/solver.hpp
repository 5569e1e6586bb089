#pragma once
// The contract between a solver's case runner and the framework.
//
// A solver registers a SolverSpec: named numeric parameters (ParamSpec, SI units, ranges) and a
// run function. The run function is pure with respect to I/O: it returns a RunOutput (tables of
// histories, particle snapshots, scalar results) and the framework writes it to HDF5. Progress
// is reported through the callback (fraction in [0,1] and a short message: simulated time, ETA).
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "cutbench/common/model.hpp"

namespace cutbench {

// Equal-length named columns, each with an SI unit, e.g. a force history (t, F_c, F_t).
struct Table {
  std::string name;
  std::vector<std::string> order;  // column order for output
  std::map<std::string, std::vector<double>> columns;
  std::map<std::string, std::string> units;

  void add(const std::string& column, const std::string& unit, std::vector<double> values) {
    if (!columns.count(column)) order.push_back(column);
    columns[column] = std::move(values);
    units[column] = unit;
  }
  std::size_t rows() const { return columns.empty() ? 0 : columns.begin()->second.size(); }
};

// Particle (or node) snapshot at one time: positions plus per-point fields, written to HDF5 with
// an XDMF index so ParaView can open it.
//
// Optional mesh (finite-element solvers): `cells` holds linear triangles, 3 point indices
// (0-based, into x/y) per cell, counter-clockwise; `cell_fields` hold one value per cell. Particle
// snapshots leave both empty and are written as point clouds, as before.
struct Snapshot {
  double time = 0.0;
  std::vector<double> x, y;
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> fields;
  std::map<std::string, std::string> units;
  std::vector<int> cells;                                  // 3 per triangle; empty: no mesh
  std::vector<std::string> cell_order;                     // output order of the cell fields
  std::map<std::string, std::vector<double>> cell_fields;  // one value per triangle
  std::map<std::string, std::string> cell_units;

  void add(const std::string& field, const std::string& unit, std::vector<double> values) {
    if (!fields.count(field)) order.push_back(field);
    fields[field] = std::move(values);
    units[field] = unit;
  }
  void add_cell_field(const std::string& field, const std::string& unit, std::vector<double> values) {
    if (!cell_fields.count(field)) cell_order.push_back(field);
    cell_fields[field] = std::move(values);
    cell_units[field] = unit;
  }
  std::size_t num_cells() const { return cells.size() / 3; }
};

struct RunOutput {
  std::vector<Table> tables;
  std::vector<Snapshot> snapshots;
  Values scalars;                              // e.g. steady F_c, transition flags
  std::map<std::string, std::string> scalar_units;
  std::vector<std::string> notes;              // assumptions and warnings, shown in the report

  // One scalar result with its unit (both maps stay in step).
  void set_scalar(const std::string& name, double value, const std::string& unit) {
    scalars[name] = value;
    scalar_units[name] = unit;
  }
};

using ProgressFn = std::function<void(double fraction, const std::string& message)>;

// One declared column of a solver's table: its name, SI unit (as the run writes it) and meaning.
struct ColumnSpec {
  std::string name, unit, description;
};

// A table a run may return (a history, a profile): declared so that case files can be checked
// against it before anything runs and `cutbench describe` can list it.
struct TableSpec {
  std::string name, description;
  std::vector<ColumnSpec> columns;
  const ColumnSpec* column(const std::string& column_name) const {
    for (const auto& c : columns) {
      if (c.name == column_name) return &c;
    }
    return nullptr;
  }
};

// The size of one run, estimated from its parameters before it starts: the number of particles
// or nodes and the memory it will hold (an upper estimate: the solver's own arrays per point).
struct Footprint {
  double points = 0.0;  // particles or nodes
  double bytes = 0.0;
  std::string what;     // "particles", "nodes"
};

struct SolverSpec {
  std::string name;         // e.g. "mpm_cutting"
  std::string description;
  std::string source;       // paper and sections
  std::vector<ParamSpec> params;
  std::vector<OutputSpec> scalars;  // the scalar results a run reports
  std::vector<TableSpec> tables;    // the tables a run may return
  bool checkpoints = false;         // runs checkpoint and resume through the shared driver
  // Footprint of a run from validated parameters (unset: small by construction, bounded ranges).
  std::function<Footprint(const Values& params)> footprint;
  std::function<RunOutput(const Values& params, const ProgressFn& progress)> run;

  const TableSpec* table(const std::string& table_name) const {
    for (const auto& t : tables) {
      if (t.name == table_name) return &t;
    }
    return nullptr;
  }
  const OutputSpec* scalar(const std::string& scalar_name) const {
    for (const auto& o : scalars) {
      if (o.name == scalar_name) return &o;
    }
    return nullptr;
  }
};

// What a run returned beyond its solver's declaration (a scalar, a table or a column not declared,
// or a column in another unit), one line each; empty when the run keeps to it.
std::vector<std::string> undeclared_outputs(const SolverSpec& spec, const RunOutput& run);

class SolverRegistry {
public:
  static SolverRegistry& instance() {
    static SolverRegistry r;
    return r;
  }
  void add(SolverSpec spec) { solvers_.push_back(std::move(spec)); }
  const SolverSpec* find(const std::string& name) const {
    for (const auto& s : solvers_) {
      if (s.name == name) return &s;
    }
    return nullptr;
  }
  const std::vector<SolverSpec>& all() const { return solvers_; }

private:
  std::vector<SolverSpec> solvers_;
};

}  // namespace cutbench
