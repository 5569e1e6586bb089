#pragma once
// Reference data: CSV files under reference_data/<paper>/ with a "# key: value" metadata header
// and a header row of "name [unit]" columns (text columns have no unit).
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cutbench::framework {

struct ReferenceColumn {
  std::string name;
  std::string unit;  // empty for text columns
  std::vector<std::string> text;
  std::vector<double> values;  // NaN where the cell is empty or not a number
};

struct ReferenceTable {
  std::filesystem::path path;
  std::map<std::string, std::string> meta;  // paper, doi, item, read, uncertainty, ...
  std::vector<ReferenceColumn> columns;
  std::size_t rows = 0;

  const ReferenceColumn& column(const std::string& name) const;  // throws InputError
  // Rows where every `where` column equals the given text (numeric columns compare as numbers).
  std::vector<std::size_t> select(const std::map<std::string, std::string>& where) const;
  // SI value of one cell (unit converted). Throws InputError for text or empty cells.
  double si_value(const std::string& column_name, std::size_t row) const;
};

// Parse a reference CSV. Throws InputError(field, ...) if the file is missing or malformed.
ReferenceTable load_reference(const std::filesystem::path& path, const std::string& field);

// Cache of loaded tables keyed by absolute path.
class ReferenceCache {
public:
  const ReferenceTable& get(const std::filesystem::path& path, const std::string& field);

private:
  std::map<std::string, ReferenceTable> tables_;
};

}  // namespace cutbench::framework
