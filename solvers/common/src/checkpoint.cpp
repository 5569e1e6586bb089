#include "cutbench/common/checkpoint.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

namespace cutbench {

namespace {
// format version in the last three characters
constexpr char kMagic[8] = {'C', 'B', 'C', 'K', 'P', '0', '0', '1'};
thread_local const CheckpointSpec* g_active = nullptr;
}  // namespace

const CheckpointSpec* active_checkpoint() { return g_active; }

CheckpointScope::CheckpointScope(CheckpointSpec spec) : spec_(std::move(spec)), previous_(g_active) {
  g_active = &spec_;
}
CheckpointScope::~CheckpointScope() { g_active = previous_; }

void write_checkpoint(const CheckpointSpec& spec, const std::function<void(BinaryWriter&)>& body) {
  namespace fs = std::filesystem;
  std::ostringstream payload(std::ios::binary);
  {
    BinaryWriter w(payload);
    body(w);
  }
  const std::string bytes = payload.str();
  const fs::path target(spec.path);
  if (target.has_parent_path()) fs::create_directories(target.parent_path());
  const std::string tmp = spec.path + "." + std::to_string(::getpid()) + ".tmp";
  {
    std::ofstream o(tmp, std::ios::binary | std::ios::trunc);
    if (!o) throw std::runtime_error("cannot write checkpoint " + tmp);
    BinaryWriter w(o);
    w.raw(kMagic, sizeof kMagic);
    w.str(spec.key);
    w.u64(bytes.size());
    w.u64(fnv1a(bytes));
    w.raw(bytes.data(), bytes.size());
    o.flush();
    if (!o) throw std::runtime_error("cannot write checkpoint " + tmp);
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot store checkpoint " + spec.path);
  }
}

bool read_checkpoint(const CheckpointSpec& spec, const std::function<void(BinaryReader&)>& body) {
  std::ifstream i(spec.path, std::ios::binary);
  if (!i) return false;
  std::string bytes;
  try {
    BinaryReader r(i);
    char magic[sizeof kMagic];
    r.raw(magic, sizeof magic);
    if (!std::equal(magic, magic + sizeof magic, kMagic)) return false;
    if (r.str() != spec.key) return false;
    const auto n = r.u64();
    const auto sum = r.u64();
    const auto pos = i.tellg();
    i.seekg(0, std::ios::end);
    const auto end = i.tellg();
    i.seekg(pos);
    if (pos < 0 || end < pos || static_cast<std::uint64_t>(end - pos) != n) return false;
    bytes.resize(n);
    r.raw(bytes.data(), n);
    if (fnv1a(bytes) != sum) return false;
  } catch (const std::exception&) {
    return false;
  }
  std::istringstream payload(bytes, std::ios::binary);
  BinaryReader r(payload);
  body(r);
  return true;
}

void remove_checkpoint(const CheckpointSpec& spec) {
  std::error_code ec;
  std::filesystem::remove(spec.path, ec);
}

CheckpointClock::CheckpointClock(const CheckpointSpec* spec, std::size_t check_every)
    : spec_(spec), check_every_(std::max<std::size_t>(1, check_every)), last_(std::chrono::steady_clock::now()) {}

bool CheckpointClock::due(std::size_t step) {
  if (!spec_ || step % check_every_ != 0) return false;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_).count();
  return elapsed >= spec_->interval_s;
}

void CheckpointClock::written() { last_ = std::chrono::steady_clock::now(); }

}  // namespace cutbench
