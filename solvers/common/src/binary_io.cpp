#include "cutbench/common/binary_io.hpp"

namespace cutbench {

void BinaryWriter::str(const std::string& s) {
  u64(s.size());
  raw(s.data(), s.size());
}

void BinaryWriter::ints(const std::vector<int>& v) {
  u64(v.size());
  for (int i : v) u64(static_cast<std::uint64_t>(static_cast<std::int64_t>(i)));
}

void BinaryWriter::strings(const std::vector<std::string>& v) {
  u64(v.size());
  for (const auto& s : v) str(s);
}

void BinaryWriter::units(const std::map<std::string, std::string>& m) {
  u64(m.size());
  for (const auto& [k, v] : m) {
    str(k);
    str(v);
  }
}

std::uint64_t BinaryReader::count(std::uint64_t item_bytes) {
  const auto n = u64();
  const auto pos = i_.tellg();
  i_.seekg(0, std::ios::end);
  const auto end = i_.tellg();
  i_.seekg(pos);
  if (pos < 0 || end < pos || n > static_cast<std::uint64_t>(end - pos) / item_bytes)
    throw std::runtime_error("corrupt binary file");
  return n;
}

std::string BinaryReader::str() {
  const auto n = count(1);
  std::string s(n, '\0');
  raw(s.data(), n);
  return s;
}

std::vector<int> BinaryReader::ints() {
  const auto n = count(8);
  std::vector<int> v(n);
  for (auto& i : v) i = static_cast<int>(static_cast<std::int64_t>(u64()));
  return v;
}

std::vector<std::string> BinaryReader::strings() {
  const auto n = count(8);
  std::vector<std::string> v;
  for (std::uint64_t k = 0; k < n; ++k) v.push_back(str());
  return v;
}

std::map<std::string, std::string> BinaryReader::units() {
  const auto n = count(16);
  std::map<std::string, std::string> m;
  for (std::uint64_t k = 0; k < n; ++k) {
    std::string key = str();
    m[key] = str();
  }
  return m;
}

void write_table(BinaryWriter& w, const Table& t) {
  w.str(t.name);
  w.u64(t.order.size());
  for (const auto& c : t.order) {
    w.str(c);
    w.str(t.units.count(c) ? t.units.at(c) : std::string());
    w.vec(t.columns.at(c));
  }
}

Table read_table(BinaryReader& r) {
  Table t;
  t.name = r.str();
  for (auto c = r.u64(); c > 0; --c) {
    const std::string col = r.str();
    const std::string unit = r.str();
    t.add(col, unit, r.vec());
  }
  return t;
}

void write_snapshot(BinaryWriter& w, const Snapshot& s) {
  w.f64(s.time);
  w.vec(s.x);
  w.vec(s.y);
  w.u64(s.order.size());
  for (const auto& f : s.order) {
    w.str(f);
    w.str(s.units.count(f) ? s.units.at(f) : std::string());
    w.vec(s.fields.at(f));
  }
  w.ints(s.cells);
  w.u64(s.cell_order.size());
  for (const auto& f : s.cell_order) {
    w.str(f);
    w.str(s.cell_units.count(f) ? s.cell_units.at(f) : std::string());
    w.vec(s.cell_fields.at(f));
  }
}

Snapshot read_snapshot(BinaryReader& r) {
  Snapshot s;
  s.time = r.f64();
  s.x = r.vec();
  s.y = r.vec();
  for (auto f = r.u64(); f > 0; --f) {
    const std::string field = r.str();
    const std::string unit = r.str();
    s.add(field, unit, r.vec());
  }
  s.cells = r.ints();
  for (auto f = r.u64(); f > 0; --f) {
    const std::string field = r.str();
    const std::string unit = r.str();
    s.add_cell_field(field, unit, r.vec());
  }
  return s;
}

std::uint64_t fnv1a(const std::string& bytes) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace cutbench
