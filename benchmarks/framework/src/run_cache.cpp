#include "cutbench/framework/run_cache.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <vector>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <iterator>
#include <sstream>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cutbench/common/binary_io.hpp"
#include "cutbench/common/checkpoint.hpp"
#include "cutbench/common/errors.hpp"
#include "cutbench/framework/results.hpp"

namespace cutbench::framework {

namespace {

// format version in the last three characters: 002 added the snapshot mesh (cells, cell fields);
// 003 ends with an FNV-1a checksum of everything before it, so that a damaged file is reported
// instead of read back (002 files, without it, are still read)
constexpr char kMagic[8] = {'C', 'B', 'R', 'U', 'N', '0', '0', '3'};
constexpr char kMagic002[8] = {'C', 'B', 'R', 'U', 'N', '0', '0', '2'};

std::uint64_t checksum_of(const std::string& bytes, std::size_t n) { return fnv1a(bytes.substr(0, n)); }

// Write all of `bytes` to `path`, flushed to the disk (fsync) before it is renamed into place.
void write_synced(const std::string& path, const std::string& bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error("cannot write run cache file " + path);
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t w = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) {
      ::close(fd);
      throw std::runtime_error("cannot write run cache file " + path);
    }
    done += static_cast<std::size_t>(w);
  }
  const bool synced = ::fsync(fd) == 0;
  if (::close(fd) != 0 || !synced) throw std::runtime_error("cannot flush run cache file " + path);
}

std::string g_cache_dir;
double g_checkpoint_interval = 600.0;
std::map<std::string, std::string> g_identity;  // solver name -> source identity of its method
std::map<std::string, std::string> g_settings;  // solver name -> build settings in that identity

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

void set_solver_identity(const std::string& solver, const std::string& identity, const std::string& settings) {
  g_identity[solver] = identity;
  g_settings[solver] = settings;
}

std::string solver_identity(const std::string& solver) {
  const auto it = g_identity.find(solver);
  return it == g_identity.end() ? std::string() : it->second;
}

std::string solver_build_settings(const std::string& solver) {
  const auto it = g_settings.find(solver);
  return it == g_settings.end() ? std::string() : it->second;
}

std::string run_key(const std::string& solver, const Values& params) {
  const std::string identity = solver_identity(solver);
  std::string key = solver + "|" +
                    (identity.empty() ? software_version() + "|build " + build_identity() : "source " + identity);
  return key + params_key(params);
}

std::string params_key(const Values& params) {
  std::string key;
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
  std::ostringstream o(std::ios::binary);
  BinaryWriter w(o);
  o.write(kMagic, sizeof kMagic);
  w.str(key);
  w.u64(run.tables.size());
  for (const auto& t : run.tables) write_table(w, t);
  w.u64(run.snapshots.size());
  for (const auto& sn : run.snapshots) write_snapshot(w, sn);
  w.u64(run.scalars.size());
  for (const auto& [name, value] : run.scalars) {
    w.str(name);
    w.f64(value);
  }
  w.units(run.scalar_units);
  w.strings(run.notes);
  std::string bytes = o.str();
  const std::uint64_t sum = checksum_of(bytes, bytes.size());
  bytes.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  std::error_code ec;
  try {
    write_synced(tmp, bytes);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot store run cache file " + path);
  }
}

bool load_run(const std::string& path, const std::string& key, RunOutput& run, std::string* problem) {
  std::ifstream i(path, std::ios::binary);
  if (!i) return false;
  std::string bytes((std::istreambuf_iterator<char>(i)), std::istreambuf_iterator<char>());
  auto fail = [&](const std::string& why) {
    if (problem) *problem = why;
    return false;
  };
  if (bytes.size() < sizeof kMagic) return fail("damaged: shorter than its header");
  const bool v3 = std::equal(kMagic, kMagic + 8, bytes.data());
  if (!v3 && !std::equal(kMagic002, kMagic002 + 8, bytes.data())) return fail("not a run file of this format");
  if (v3) {
    if (bytes.size() < sizeof kMagic + 8) return fail("damaged: truncated");
    std::uint64_t sum = 0;
    std::memcpy(&sum, bytes.data() + bytes.size() - 8, sizeof sum);
    bytes.resize(bytes.size() - 8);
    if (checksum_of(bytes, bytes.size()) != sum) return fail("damaged: checksum mismatch");
  }
  std::istringstream in(bytes.substr(sizeof kMagic), std::ios::binary);
  try {
    BinaryReader r(in);
    if (r.str() != key) return false;  // another run's file: not a problem
    RunOutput out;
    for (auto n = r.u64(); n > 0; --n) out.tables.push_back(read_table(r));
    for (auto n = r.u64(); n > 0; --n) out.snapshots.push_back(read_snapshot(r));
    for (auto n = r.u64(); n > 0; --n) {
      const std::string name = r.str();
      out.scalars[name] = r.f64();
    }
    out.scalar_units = r.units();
    out.notes = r.strings();
    run = std::move(out);
    return true;
  } catch (const std::exception& e) {
    return fail(std::string("damaged: ") + e.what());
  }
}

RunLock::RunLock(const std::string& run_path, const std::function<void(const std::string&)>& waiting)
    : path_(run_path.substr(0, run_path.size() - 4) + ".lock") {
  char host[256] = {0};
  ::gethostname(host, sizeof host - 1);
  const std::string me = std::to_string(::getpid()) + " " + host + "\n";
  bool told = false;
  while (true) {
    const int fd = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd >= 0) {
      const bool ok = ::write(fd, me.data(), me.size()) == static_cast<ssize_t>(me.size());
      ::close(fd);
      if (ok) return;
      ::unlink(path_.c_str());
      throw std::runtime_error("cannot write lock " + path_);
    }
    if (errno != EEXIST) throw std::runtime_error("cannot create lock " + path_ + ": " + std::strerror(errno));
    // held: by a live process (wait for it), or by one that died (take the lock over)
    std::ifstream in(path_);
    long pid = 0;
    std::string holder_host;
    in >> pid >> holder_host;
    const bool same_host = holder_host == host;
    const bool dead = in && same_host && pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
    // a lock left empty by a holder killed between creating and writing it (not one just created)
    struct stat st {};
    const bool empty_and_old = !in && holder_host.empty() && ::stat(path_.c_str(), &st) == 0 &&
                               std::difftime(std::time(nullptr), st.st_mtime) > 10.0;
    if (dead || empty_and_old) {
      ::unlink(path_.c_str());
      continue;
    }
    if (!told && waiting) waiting("computed by process " + std::to_string(pid) + " on " + holder_host + ": waiting for it");
    told = true;
    waited_ = true;
    ::sleep(2);
  }
}

RunLock::~RunLock() { ::unlink(path_.c_str()); }

std::string run_lock_holder(const std::string& run_path) {
  if (!run_in_progress(run_path)) return "";
  std::ifstream in(run_path.substr(0, run_path.size() - 4) + ".lock");
  long pid = 0;
  std::string host;
  in >> pid >> host;
  return "pid " + std::to_string(pid) + " on " + host;
}

namespace {
std::string progress_path(const std::string& run_path) { return run_path.substr(0, run_path.size() - 4) + ".progress"; }
double unix_now() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}
}  // namespace

ProgressLog::ProgressLog(std::string run_path, double interval_s)
    : path_(progress_path(run_path)), interval_s_(interval_s) {}

void ProgressLog::note(double fraction) {
  const double now = unix_now();
  if (now - last_ < interval_s_ || !std::isfinite(fraction)) return;
  last_ = now;
  std::FILE* f = std::fopen(path_.c_str(), "a");  // a progress line that cannot be written is skipped
  if (!f) return;
  std::fprintf(f, "%.0f %.6f\n", now, std::clamp(fraction, 0.0, 1.0));
  std::fclose(f);
}

void ProgressLog::remove() { ::unlink(path_.c_str()); }

double run_progress(const std::string& run_path, double not_after) {
  std::ifstream in(progress_path(run_path));
  double t = 0.0, f = 0.0, best = -1.0;
  while (in >> t >> f) {
    if (t <= not_after) best = f;
  }
  return best;
}

double run_fraction_done(const std::string& run_path, bool running) {
  if (running) return run_progress(run_path, HUGE_VAL);
  struct stat st {};
  const std::string ckpt = run_path.substr(0, run_path.size() - 4) + ".ckpt";
  if (::stat(ckpt.c_str(), &st) != 0) return -1.0;
  return run_progress(run_path, static_cast<double>(st.st_mtim.tv_sec) + 1.0);
}

bool run_in_progress(const std::string& run_path) {
  std::ifstream in(run_path.substr(0, run_path.size() - 4) + ".lock");
  long pid = 0;
  std::string holder_host;
  if (!(in >> pid >> holder_host) || pid <= 0) return false;
  char host[256] = {0};
  ::gethostname(host, sizeof host - 1);
  // another host's holder cannot be checked: live, as RunLock takes it
  return holder_host != host || ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH;
}

namespace {
// The magic and key at the start of a run file or a checkpoint ("" when neither).
std::string stored_key(const std::string& path, std::string& kind) {
  // the checkpoint format's magic (solvers/common/src/checkpoint.cpp)
  static constexpr char kCheckpointMagic[8] = {'C', 'B', 'C', 'K', 'P', '0', '0', '1'};
  std::ifstream i(path, std::ios::binary);
  char magic[8];
  if (!i.read(magic, sizeof magic)) return "";
  if (std::equal(magic, magic + 8, kMagic) || std::equal(magic, magic + 8, kMagic002)) {
    kind = "run";
  } else if (std::equal(magic, magic + 8, kCheckpointMagic)) {
    kind = "checkpoint";
  } else {
    return "";
  }
  try {
    BinaryReader r(i);
    return r.str();
  } catch (const std::exception&) {
    return "";
  }
}

// "solver|source <id>|a=1|b=2" (or "solver|<version>|build <hash>|...") into its parts.
void parse_key(const std::string& key, StoredRun& s) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const auto bar = key.find('|', start);
    parts.push_back(key.substr(start, bar == std::string::npos ? std::string::npos : bar - start));
    if (bar == std::string::npos) break;
    start = bar + 1;
  }
  s.solver = parts.front();
  for (std::size_t k = 1; k < parts.size(); ++k) {
    const std::string& p = parts[k];
    if (p.rfind("source ", 0) == 0) {
      s.identity = p.substr(7);
      continue;
    }
    const auto eq = p.find('=');
    if (eq == std::string::npos) continue;  // version or executable hash of an old key
    s.params[p.substr(0, eq)] = std::strtod(p.c_str() + eq + 1, nullptr);
  }
}
}  // namespace

std::vector<StoredRun> scan_run_store(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError("runs", "a directory of stored runs ('" + dir + "' is not one)");
  std::vector<StoredRun> out;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string ext = e.path().extension().string();
    if (!e.is_regular_file() || (ext != ".run" && ext != ".ckpt")) continue;
    StoredRun s;
    s.file = e.path().filename().string();
    s.kind = ext == ".run" ? "run" : "checkpoint";
    s.key = stored_key(e.path().string(), s.kind);
    if (s.key.empty()) {
      s.state = "unreadable";
      out.push_back(std::move(s));
      continue;
    }
    parse_key(s.key, s);
    const std::string current = solver_identity(s.solver);
    if (s.identity.empty()) {
      s.state = "executable-keyed";
    } else if (current.empty()) {
      s.state = "unknown solver";
    } else {
      s.state = s.identity == current ? "current" : "stale";
    }
    if (s.kind == "run") {
      RunOutput run;
      std::string problem;
      if (!load_run(e.path().string(), s.key, run, &problem)) {
        s.state = problem.rfind("damaged", 0) == 0 ? problem : "unreadable";
      } else {
        for (const auto& n : run.notes) {
          if (n.rfind("run stored in the run cache:", 0) == 0) s.provenance = n;
        }
        s.scalars = std::move(run.scalars);
        s.scalar_units = std::move(run.scalar_units);
      }
    }
    out.push_back(std::move(s));
  }
  if (ec) throw InputError("runs", "a readable directory ('" + dir + "': " + ec.message() + ")");
  std::sort(out.begin(), out.end(), [](const StoredRun& a, const StoredRun& b) { return a.file < b.file; });
  return out;
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

namespace {
bool g_stored_only = false;
}
void set_run_cache_stored_only(bool on) { g_stored_only = on; }
bool run_cache_stored_only() { return g_stored_only; }

void set_checkpoint_interval(double seconds) {
  if (!(seconds > 0.0 && seconds <= 1e7))
    throw InputError("--checkpoint-minutes", "a positive number of minutes (at most 1e7 s)");
  g_checkpoint_interval = seconds;
}
double checkpoint_interval() { return g_checkpoint_interval; }

}  // namespace cutbench::framework
