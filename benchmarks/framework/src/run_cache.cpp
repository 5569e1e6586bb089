#include "cutbench/framework/run_cache.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include <unistd.h>

#include "cutbench/common/errors.hpp"
#include "cutbench/framework/results.hpp"

namespace cutbench::framework {

namespace {

// format version in the last three characters: 002 added the snapshot mesh (cells, cell fields)
constexpr char kMagic[8] = {'C', 'B', 'R', 'U', 'N', '0', '0', '2'};

std::string g_cache_dir;

std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

class Writer {
public:
  explicit Writer(std::ofstream& o) : o_(o) {}
  void u64(std::uint64_t v) { o_.write(reinterpret_cast<const char*>(&v), sizeof v); }
  void f64(double v) { o_.write(reinterpret_cast<const char*>(&v), sizeof v); }
  void str(const std::string& s) {
    u64(s.size());
    o_.write(s.data(), static_cast<std::streamsize>(s.size()));
  }
  void vec(const std::vector<double>& v) {
    u64(v.size());
    o_.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(double)));
  }
  void ints(const std::vector<int>& v) {
    u64(v.size());
    for (int i : v) u64(static_cast<std::uint64_t>(static_cast<std::int64_t>(i)));
  }
  void strings(const std::vector<std::string>& v) {
    u64(v.size());
    for (const auto& s : v) str(s);
  }
  void units(const std::map<std::string, std::string>& m) {
    u64(m.size());
    for (const auto& [k, v] : m) {
      str(k);
      str(v);
    }
  }

private:
  std::ofstream& o_;
};

class Reader {
public:
  explicit Reader(std::ifstream& i) : i_(i) {}
  std::uint64_t u64() {
    std::uint64_t v = 0;
    i_.read(reinterpret_cast<char*>(&v), sizeof v);
    check();
    return v;
  }
  double f64() {
    double v = 0.0;
    i_.read(reinterpret_cast<char*>(&v), sizeof v);
    check();
    return v;
  }
  std::string str() {
    const auto n = count(1);
    std::string s(n, '\0');
    i_.read(s.data(), static_cast<std::streamsize>(n));
    check();
    return s;
  }
  std::vector<double> vec() {
    const auto n = count(sizeof(double));
    std::vector<double> v(n);
    i_.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(double)));
    check();
    return v;
  }
  std::vector<int> ints() {
    const auto n = count(8);
    std::vector<int> v(n);
    for (auto& i : v) i = static_cast<int>(static_cast<std::int64_t>(u64()));
    return v;
  }
  std::vector<std::string> strings() {
    const auto n = count(8);
    std::vector<std::string> v;
    for (std::uint64_t k = 0; k < n; ++k) v.push_back(str());
    return v;
  }
  std::map<std::string, std::string> units() {
    const auto n = count(16);
    std::map<std::string, std::string> m;
    for (std::uint64_t k = 0; k < n; ++k) {
      std::string key = str();
      m[key] = str();
    }
    return m;
  }

private:
  std::ifstream& i_;
  void check() {
    if (!i_) throw std::runtime_error("truncated run file");
  }
  // a count read from the file, bounded by what is left of it (guards against corrupt sizes)
  std::uint64_t count(std::uint64_t item_bytes) {
    const auto n = u64();
    const auto pos = i_.tellg();
    i_.seekg(0, std::ios::end);
    const auto end = i_.tellg();
    i_.seekg(pos);
    if (n > static_cast<std::uint64_t>(end - pos) / item_bytes) throw std::runtime_error("corrupt run file");
    return n;
  }
};

}  // namespace

// Identity of the running build: a hash of the executable's bytes, so that any rebuild with
// changed code (committed or not) gives new keys; empty when the executable cannot be read.
const std::string& build_identity() {
  static const std::string id = [] {
    std::ifstream exe("/proc/self/exe", std::ios::binary);
    if (!exe) return std::string();
    std::uint64_t h = 1469598103934665603ull;
    std::vector<char> buf(1 << 16);
    std::uint64_t n = 0;
    while (exe) {
      exe.read(buf.data(), static_cast<std::streamsize>(buf.size()));
      const auto got = exe.gcount();
      for (std::streamsize k = 0; k < got; ++k) {
        h ^= static_cast<unsigned char>(buf[static_cast<std::size_t>(k)]);
        h *= 1099511628211ull;
      }
      n += static_cast<std::uint64_t>(got);
    }
    if (n == 0) return std::string();
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
    return std::string(hex);
  }();
  return id;
}

std::string run_key(const std::string& solver, const Values& params) {
  std::string key = solver + "|" + software_version() + "|build " + build_identity();
  char buf[64];
  for (const auto& [name, value] : params) {
    std::snprintf(buf, sizeof buf, "%.17g", value);
    key += "|" + name + "=" + buf;
  }
  return key;
}

std::string run_file_name(const std::string& solver, const std::string& key) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fnv1a(key)));
  return solver + "-" + hex + ".run";
}

void save_run(const std::string& path, const std::string& key, const RunOutput& run) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  if (target.has_parent_path()) fs::create_directories(target.parent_path());
  static std::uint64_t counter = 0;
  const std::string tmp = path + "." + std::to_string(::getpid()) + "." + std::to_string(++counter) + ".tmp";
  {
    std::ofstream o(tmp, std::ios::binary | std::ios::trunc);
    if (!o) throw std::runtime_error("cannot write run cache file " + tmp);
    Writer w(o);
    o.write(kMagic, sizeof kMagic);
    w.str(key);
    w.u64(run.tables.size());
    for (const auto& t : run.tables) {
      w.str(t.name);
      w.u64(t.order.size());
      for (const auto& c : t.order) {
        w.str(c);
        w.str(t.units.count(c) ? t.units.at(c) : std::string());
        w.vec(t.columns.at(c));
      }
    }
    w.u64(run.snapshots.size());
    for (const auto& s : run.snapshots) {
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
    w.u64(run.scalars.size());
    for (const auto& [name, value] : run.scalars) {
      w.str(name);
      w.f64(value);
    }
    w.units(run.scalar_units);
    w.strings(run.notes);
    if (!o) throw std::runtime_error("cannot write run cache file " + tmp);
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot store run cache file " + path);
  }
}

bool load_run(const std::string& path, const std::string& key, RunOutput& run) {
  std::ifstream i(path, std::ios::binary);
  if (!i) return false;
  try {
    char magic[sizeof kMagic];
    i.read(magic, sizeof magic);
    if (!i || !std::equal(magic, magic + sizeof magic, kMagic)) return false;
    Reader r(i);
    if (r.str() != key) return false;
    RunOutput out;
    for (auto n = r.u64(); n > 0; --n) {
      Table t;
      t.name = r.str();
      for (auto c = r.u64(); c > 0; --c) {
        const std::string col = r.str();
        const std::string unit = r.str();
        t.add(col, unit, r.vec());
      }
      out.tables.push_back(std::move(t));
    }
    for (auto n = r.u64(); n > 0; --n) {
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
      out.snapshots.push_back(std::move(s));
    }
    for (auto n = r.u64(); n > 0; --n) {
      const std::string name = r.str();
      out.scalars[name] = r.f64();
    }
    out.scalar_units = r.units();
    out.notes = r.strings();
    run = std::move(out);
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

void set_run_cache_dir(const std::string& dir) {
  namespace fs = std::filesystem;
  if (!dir.empty()) {
    if (build_identity().empty())
      throw InputError("--run-cache", "the running executable cannot be read (/proc/self/exe), so runs cannot be keyed to this build");
    std::error_code ec;
    fs::create_directories(dir, ec);
    const fs::path probe = fs::path(dir) / (".write-test." + std::to_string(::getpid()));
    { std::ofstream o(probe); if (!o || ec) throw InputError("--run-cache", "a writable directory (cannot create or write '" + dir + "')"); }
    fs::remove(probe, ec);
  }
  g_cache_dir = dir;
}
const std::string& run_cache_dir() { return g_cache_dir; }

}  // namespace cutbench::framework
