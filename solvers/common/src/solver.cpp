#include "cutbench/common/solver.hpp"

namespace cutbench {

std::vector<std::string> undeclared_outputs(const SolverSpec& spec, const RunOutput& run) {
  std::vector<std::string> out;
  for (const auto& [name, value] : run.scalars) {
    (void)value;
    if (!spec.scalar(name)) out.push_back("scalar '" + name + "'");
  }
  for (const auto& t : run.tables) {
    const TableSpec* ts = spec.table(t.name);
    if (!ts) {
      out.push_back("table '" + t.name + "'");
      continue;
    }
    for (const auto& c : t.order) {
      const ColumnSpec* cs = ts->column(c);
      const auto unit = t.units.find(c);
      if (!cs) {
        out.push_back("column '" + c + "' of table '" + t.name + "'");
      } else if (unit != t.units.end() && unit->second != cs->unit) {
        out.push_back("column '" + c + "' of table '" + t.name + "' in " + unit->second + " (declared " + cs->unit + ")");
      }
    }
  }
  return out;
}

}  // namespace cutbench
