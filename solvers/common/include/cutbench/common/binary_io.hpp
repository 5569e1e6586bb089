#pragma once
// Little binary streams shared by the run cache (benchmarks/framework) and solver checkpoints:
// native-endian 64-bit counts and doubles, length-prefixed strings and arrays. A reader checks
// every read and bounds every count by what is left of the stream, so a truncated or corrupt
// file throws std::runtime_error instead of allocating or reading garbage.
#include <cstdint>
#include <istream>
#include <map>
#include <ostream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "cutbench/common/solver.hpp"

namespace cutbench {

class BinaryWriter {
public:
  explicit BinaryWriter(std::ostream& o) : o_(o) {}
  void u64(std::uint64_t v) { raw(&v, sizeof v); }
  void f64(double v) { raw(&v, sizeof v); }
  void str(const std::string& s);
  void vec(const std::vector<double>& v) { pods(v); }
  void ints(const std::vector<int>& v);  // as 64-bit signed values
  void strings(const std::vector<std::string>& v);
  void units(const std::map<std::string, std::string>& m);
  // A vector of plain records (doubles, chars, fixed-size Eigen vectors and matrices) copied bytewise.
  template <class T>
  void pods(const std::vector<T>& v) {
    static_assert(std::is_standard_layout_v<T>, "bytewise records only");
    u64(v.size());
    raw(v.data(), v.size() * sizeof(T));
  }
  void raw(const void* data, std::size_t bytes) {
    o_.write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
  }

private:
  std::ostream& o_;
};

class BinaryReader {
public:
  explicit BinaryReader(std::istream& i) : i_(i) {}
  std::uint64_t u64() {
    std::uint64_t v = 0;
    raw(&v, sizeof v);
    return v;
  }
  double f64() {
    double v = 0.0;
    raw(&v, sizeof v);
    return v;
  }
  std::string str();
  std::vector<double> vec() { return pods<double>(); }
  std::vector<int> ints();
  std::vector<std::string> strings();
  std::map<std::string, std::string> units();
  template <class T>
  std::vector<T> pods() {
    static_assert(std::is_standard_layout_v<T>, "bytewise records only");
    const auto n = count(sizeof(T));
    std::vector<T> v(n);
    raw(v.data(), n * sizeof(T));
    return v;
  }
  void raw(void* data, std::size_t bytes) {
    i_.read(static_cast<char*>(data), static_cast<std::streamsize>(bytes));
    if (!i_) throw std::runtime_error("truncated binary file");
  }
  // A count read from the stream, bounded by what is left of it (guards against corrupt sizes).
  std::uint64_t count(std::uint64_t item_bytes);

private:
  std::istream& i_;
};

// Tables and snapshots (every field, unit and mesh) in the order of their `order` lists.
void write_table(BinaryWriter& w, const Table& t);
Table read_table(BinaryReader& r);
void write_snapshot(BinaryWriter& w, const Snapshot& s);
Snapshot read_snapshot(BinaryReader& r);

// FNV-1a 64-bit hash of a byte string (file names of keys, checkpoint checksums).
std::uint64_t fnv1a(const std::string& bytes);

}  // namespace cutbench
