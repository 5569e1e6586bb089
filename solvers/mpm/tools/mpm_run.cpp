// mpm_run: run the mpm_cutting solver from the command line (until the framework CLI drives it).
//   mpm_run key=value ... [csv=PATH] [snapcsv=PREFIX]
// Values are SI numbers. Prints the scalar results; writes the force history as CSV if asked.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>

#include "cutbench/common/errors.hpp"
#include "cutbench/mpm/cutting.hpp"

int main(int argc, char** argv) {
  using namespace cutbench;
  Values params;
  std::string csv, snap;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto eq = a.find('=');
    if (eq == std::string::npos) {
      std::fprintf(stderr, "usage: mpm_run key=value ... [csv=PATH] [snapcsv=PREFIX]\n");
      return 2;
    }
    const std::string k = a.substr(0, eq), val = a.substr(eq + 1);
    if (k == "csv") {
      csv = val;
    } else if (k == "snapcsv") {
      snap = val;
    } else {
      params[k] = std::strtod(val.c_str(), nullptr);
    }
  }
  try {
    const RunOutput out = mpm::run_cutting(params, [](double f, const std::string& m) {
      if (static_cast<int>(f * 100) % 10 == 0) std::fprintf(stderr, "%3.0f%% %s\n", 100 * f, m.c_str());
    });
    for (const auto& [k, v] : out.scalars) std::printf("%-22s %.6g %s\n", k.c_str(), v, out.scalar_units.at(k).c_str());
    for (const auto& n : out.notes) std::printf("note: %s\n", n.c_str());
    if (!csv.empty()) {
      std::ofstream f(csv);
      const Table& t = out.tables.front();
      for (std::size_t c = 0; c < t.order.size(); ++c) f << (c ? "," : "") << t.order[c] << " [" << t.units.at(t.order[c]) << "]";
      f << "\n";
      for (std::size_t r = 0; r < t.rows(); ++r) {
        for (std::size_t c = 0; c < t.order.size(); ++c) f << (c ? "," : "") << t.columns.at(t.order[c])[r];
        f << "\n";
      }
    }
    if (!snap.empty()) {
      for (std::size_t s = 0; s < out.snapshots.size(); ++s) {
        const Snapshot& sn = out.snapshots[s];
        std::ofstream f(snap + std::to_string(s) + ".csv");
        f << "x,y";
        for (const auto& n : sn.order) f << "," << n;
        f << "\n";
        for (std::size_t p = 0; p < sn.x.size(); ++p) {
          f << sn.x[p] << "," << sn.y[p];
          for (const auto& n : sn.order) f << "," << sn.fields.at(n)[p];
          f << "\n";
        }
      }
    }
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
