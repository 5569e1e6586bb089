#include "cutbench/framework/reference.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

#include "cutbench/common/errors.hpp"
#include "cutbench/common/units.hpp"

namespace cutbench::framework {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

// Split one CSV line; supports double-quoted cells with commas.
std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> cells;
  std::string cur;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"') {
      if (quoted && i + 1 < line.size() && line[i + 1] == '"') {
        cur += '"';
        ++i;
      } else {
        quoted = !quoted;
      }
    } else if (c == ',' && !quoted) {
      cells.push_back(trim(cur));
      cur.clear();
    } else {
      cur += c;
    }
  }
  cells.push_back(trim(cur));
  return cells;
}

bool parse_number(const std::string& s, double& out) {
  if (s.empty()) return false;
  const char* b = s.c_str();
  char* e = nullptr;
  out = std::strtod(b, &e);
  return e != b && trim(std::string(e)).empty();
}

}  // namespace

const ReferenceColumn& ReferenceTable::column(const std::string& name) const {
  for (const auto& c : columns) {
    if (c.name == name) return c;
  }
  std::string known;
  for (const auto& c : columns) known += (known.empty() ? "" : ", ") + c.name;
  throw InputError("reference.column", "no column '" + name + "' in " + path.string() +
                                            " (columns: " + known + ")");
}


std::vector<std::size_t> ReferenceTable::select(const std::map<std::string, std::string>& where) const {
  std::vector<std::size_t> rows_out;
  for (std::size_t r = 0; r < rows; ++r) {
    bool ok = true;
    for (const auto& [name, want] : where) {
      const auto& col = column(name);
      double w = 0.0;
      if (!col.unit.empty() && parse_number(want, w)) {
        const double v = col.values[r];
        ok = std::isfinite(v) && std::abs(v - w) <= 1e-12 * std::max(1.0, std::abs(w));
      } else {
        ok = col.text[r] == want;
      }
      if (!ok) break;
    }
    if (ok) rows_out.push_back(r);
  }
  return rows_out;
}

double ReferenceTable::si_value(const std::string& column_name, std::size_t row) const {
  const auto& col = column(column_name);
  if (col.unit.empty()) {
    throw InputError("reference.column", "column '" + column_name + "' of " + path.string() +
                                              " is text, not a number");
  }
  if (row >= rows || !std::isfinite(col.values[row])) {
    throw InputError("reference", "empty cell in column '" + column_name + "' row " +
                                      std::to_string(row + 1) + " of " + path.string());
  }
  return to_si(col.values[row], col.unit, "reference.column " + column_name);
}

ReferenceTable load_reference(const std::filesystem::path& path, const std::string& field) {
  std::ifstream in(path);
  if (!in) throw InputError(field, "reference file not found: " + path.string());
  ReferenceTable t;
  t.path = path;
  std::string line;
  bool have_header = false;
  std::size_t lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    const std::string s = trim(line);
    if (s.empty()) continue;
    if (s[0] == '#') {
      const auto colon = s.find(':');
      if (colon != std::string::npos) {
        std::string key = trim(s.substr(1, colon - 1));
        std::string value = trim(s.substr(colon + 1));
        if (!key.empty() && key.find(' ') == std::string::npos) {
          auto& slot = t.meta[key];
          slot = slot.empty() ? value : slot + " " + value;
        }
      }
      continue;
    }
    auto cells = split_csv(s);
    if (!have_header) {
      for (const auto& cell : cells) {
        ReferenceColumn c;
        const auto lb = cell.find('[');
        if (lb != std::string::npos) {
          const auto rb = cell.find(']', lb);
          if (rb == std::string::npos) {
            throw InputError(field, path.string() + ": unclosed '[' in header cell '" + cell + "'");
          }
          c.name = trim(cell.substr(0, lb));
          c.unit = trim(cell.substr(lb + 1, rb - lb - 1));
          unit_info(c.unit, field + " (" + path.filename().string() + " column " + c.name + ")");
        } else {
          c.name = cell;
        }
        t.columns.push_back(std::move(c));
      }
      have_header = true;
      continue;
    }
    if (cells.size() != t.columns.size()) {
      throw InputError(field, path.string() + ":" + std::to_string(lineno) + ": expected " +
                                  std::to_string(t.columns.size()) + " cells, found " +
                                  std::to_string(cells.size()));
    }
    for (std::size_t i = 0; i < cells.size(); ++i) {
      auto& c = t.columns[i];
      c.text.push_back(cells[i]);
      double v = std::numeric_limits<double>::quiet_NaN();
      if (!c.unit.empty() && !cells[i].empty() && !parse_number(cells[i], v)) {
        throw InputError(field, path.string() + ":" + std::to_string(lineno) + ": column '" +
                                    c.name + "' [" + c.unit + "] holds non-number '" + cells[i] + "'");
      }
      c.values.push_back(v);
    }
    ++t.rows;
  }
  if (!have_header) throw InputError(field, path.string() + ": no header row");
  return t;
}

const ReferenceTable& ReferenceCache::get(const std::filesystem::path& path, const std::string& field) {
  const std::string key = std::filesystem::absolute(path).lexically_normal().string();
  auto it = tables_.find(key);
  if (it == tables_.end()) it = tables_.emplace(key, load_reference(path, field)).first;
  return it->second;
}

}  // namespace cutbench::framework
