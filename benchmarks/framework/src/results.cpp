#include "cutbench/framework/results.hpp"

#include <hdf5.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

#include "cutbench/common/errors.hpp"

#ifndef CUTBENCH_VERSION
#define CUTBENCH_VERSION "0.0.0"
#endif

namespace cutbench::framework {
namespace detail {
const char* git_sha();  // generated at every build (cmake/git_version.cmake)
}  // namespace detail
namespace fs = std::filesystem;

std::string software_version() { return std::string(CUTBENCH_VERSION) + "+" + detail::git_sha(); }

std::string utc_now_iso() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

namespace {

json num_or_null(double v, bool has) { return has && std::isfinite(v) ? json(v) : json(nullptr); }

// --- small RAII + helpers over the HDF5 C API -------------------------------------------------
struct H5Id {
  hid_t id = -1;
  herr_t (*close)(hid_t) = nullptr;
  H5Id(hid_t i, herr_t (*c)(hid_t)) : id(i), close(c) {
    if (id < 0) throw std::runtime_error("HDF5 call failed");
  }
  ~H5Id() {
    if (id >= 0 && close) close(id);
  }
  H5Id(const H5Id&) = delete;
  H5Id& operator=(const H5Id&) = delete;
  operator hid_t() const { return id; }
};

void attr_string(hid_t obj, const std::string& name, const std::string& value) {
  H5Id type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  H5Id space(H5Screate(H5S_SCALAR), H5Sclose);
  H5Id attr(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  const char* p = value.c_str();
  H5Awrite(attr, type, &p);
}

void attr_double(hid_t obj, const std::string& name, double value) {
  H5Id space(H5Screate(H5S_SCALAR), H5Sclose);
  H5Id attr(H5Acreate2(obj, name.c_str(), H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  H5Awrite(attr, H5T_NATIVE_DOUBLE, &value);
}

void dataset(hid_t group, const std::string& name, const std::vector<double>& v, const std::string& unit) {
  hsize_t dims[1] = {v.size()};
  H5Id space(H5Screate_simple(1, dims, nullptr), H5Sclose);
  H5Id ds(H5Dcreate2(group, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
  if (!v.empty()) H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  attr_string(ds, "units", unit);
}

// The connectivity of a snapshot's triangles as an (n_cells, 3) int64 dataset "cells".
void write_cells(hid_t group, const Snapshot& snap) {
  const std::size_t nc = snap.num_cells();
  std::vector<long long> c(snap.cells.begin(), snap.cells.end());
  hsize_t dims[2] = {nc, 3};
  H5Id space(H5Screate_simple(2, dims, nullptr), H5Sclose);
  H5Id ds(H5Dcreate2(group, "cells", H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
  if (!c.empty()) H5Dwrite(ds, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, c.data());
  attr_string(ds, "topology", "triangle");
  attr_string(ds, "units", "1");
}

// A snapshot whose arrays disagree in length would give a broken XDMF grid: refuse it.
void check_snapshot(const Snapshot& snap, const std::string& where) {
  const std::size_t n = snap.x.size();
  auto bad = [&](const std::string& what) { throw std::runtime_error("snapshot " + where + ": " + what); };
  if (snap.y.size() != n) bad("x and y differ in length");
  for (const auto& f : snap.order)
    if (snap.fields.at(f).size() != n) bad("point field '" + f + "' has not one value per point");
  if (snap.cells.size() % 3 != 0) bad("cells is not a multiple of 3 (triangles)");
  for (int i : snap.cells)
    if (i < 0 || static_cast<std::size_t>(i) >= n) bad("a cell refers to point " + std::to_string(i) + " of " + std::to_string(n));
  for (const auto& f : snap.cell_order)
    if (snap.cell_fields.at(f).size() != snap.num_cells()) bad("cell field '" + f + "' has not one value per cell");
  if (snap.cells.empty() && !snap.cell_order.empty()) bad("cell fields without cells");
}

hid_t make_group(hid_t parent, const std::string& name) {
  return H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
}

// The columns of a table as datasets of `group` (units attribute each), plus their order.
void write_columns(hid_t group, const Table& t) {
  std::string order;
  for (const auto& c : t.order) {
    dataset(group, c, t.columns.at(c), t.units.at(c));
    order += (order.empty() ? "" : ",") + c;
  }
  attr_string(group, "columns", order);
}

void write_table(hid_t parent, const Table& t) {
  H5Id g(make_group(parent, t.name), H5Gclose);
  write_columns(g, t);
}

}  // namespace

json check_to_json(const CheckRecord& r) {
  json j;
  j["case"] = r.case_id;
  j["key"] = r.key;
  j["kind"] = r.kind;
  j["metric"] = r.metric;
  j["units"] = r.units;
  j["value"] = num_or_null(r.value, r.has_value);
  if (r.is_range) {
    j["reference"] = json::array({num_or_null(r.lower, r.has_reference), num_or_null(r.upper, r.has_reference)});
  } else {
    j["reference"] = num_or_null(r.reference, r.has_reference);
  }
  j["error"] = num_or_null(r.error, r.has_value && r.has_reference);
  j["tolerance"] = r.is_range ? json(nullptr) : json(r.tolerance);
  j["tolerance_type"] = r.is_range ? "range" : (r.relative_tol ? "relative" : "absolute");
  j["status"] = r.status;
  j["source"] = r.source;
  if (!r.known_failure.empty()) j["known_failure"] = r.known_failure;
  if (!r.finding.empty()) j["finding"] = r.finding;
  if (!r.tolerance_source.empty()) j["tolerance_source"] = r.tolerance_source;
  if (r.scatter > 0) {
    j["scatter"] = r.scatter;
    j["scatter_source"] = r.scatter_source;
  }
  if (!r.audit.empty()) j["audit"] = r.audit;
  if (!r.description.empty()) j["description"] = r.description;
  if (!r.message.empty()) j["message"] = r.message;
  return j;
}

json case_result_to_json(const CaseSpec& spec, const CaseResult& r) {
  json j;
  j["case"] = spec.id;
  j["paper"] = spec.paper;
  j["item"] = spec.item;
  j["title"] = spec.title;
  if (!spec.claim.empty()) j["claim"] = spec.claim;
  j["tier"] = r.tier;
  j["solver"] = spec.solver;
  if (!r.solver_sources.empty()) j["solver_sources"] = r.solver_sources;
  j["status"] = r.status;
  j["date"] = r.date;
  j["software"] = software_version();
  j["wall_time_s"] = r.wall_time_s;
  j["threads"] = r.threads;
  int unexpected = 0;
  for (const auto& c : r.checks) unexpected += (c.status == "FAIL" && c.known_failure.empty()) ? 1 : 0;
  j["unexpected_failures"] = unexpected;
  j["audited"] = true;  // every PASS/FAIL check carries the perturbation audit (empty `audit`: can fail)
  j["checks"] = json::array();
  for (const auto& c : r.checks) j["checks"].push_back(check_to_json(c));
  json notes = json::array();
  for (const auto& s : r.series) {
    for (const auto& n : s.notes) notes.push_back(s.name + ": " + n);
    if (!s.error.empty()) notes.push_back(s.name + ": ERROR " + s.error);
  }
  j["notes"] = notes;
  return j;
}

void write_atomic(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  const fs::path tmp = path.string() + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
    out << text;
    if (!out) throw std::runtime_error("write failed: " + tmp.string());
  }
  fs::rename(tmp, path);
}

namespace {
// Text for an XML attribute or element: the five markup characters as entities.
std::string xml_escape(const std::string& text) {
  std::string out;
  for (const char ch : text) {
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += ch;
    }
  }
  return out;
}
}  // namespace

fs::path write_hdf5(const CaseSpec& spec, const CaseResult& result, const fs::path& out_dir) {
  const fs::path dir = out_dir / spec.paper;
  fs::create_directories(dir);
  const fs::path final_path = dir / (spec.item_id + ".h5");
  const fs::path tmp = final_path.string() + ".tmp." + std::to_string(::getpid());
  for (const auto& s : result.series)  // before anything is written
    for (std::size_t k = 0; k < s.runs.size(); ++k)
      for (std::size_t j = 0; j < s.runs[k].snapshots.size(); ++j)
        check_snapshot(s.runs[k].snapshots[j], s.name + "/point_" + std::to_string(k) + "/" + std::to_string(j));
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  std::ostringstream xdmf;
  bool have_snapshots = false;
  {
    H5Id file(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
    attr_string(file, "software", "cutbench");
    attr_string(file, "software_version", software_version());
    attr_string(file, "date", result.date);
    attr_string(file, "case_id", spec.id);
    attr_string(file, "paper", spec.paper);
    const auto inv = load_inventory(source_root(), spec.paper);
    attr_string(file, "paper_doi", inv.meta.count("doi") ? inv.meta.at("doi") : "unknown");
    attr_string(file, "paper_citation", inv.meta.count("citation") ? inv.meta.at("citation") : "unknown");
    attr_string(file, "item", spec.item);
    attr_string(file, "title", spec.title);
    attr_string(file, "tier", result.tier);
    attr_string(file, "status", result.status);
    attr_double(file, "threads", result.threads);
    attr_double(file, "wall_time_s", result.wall_time_s);
    json params = json::object();
    for (const auto& s : spec.series) {
      json p = json::object();
      for (const auto& [k, v] : s.params) p[k] = v;
      params[s.name] = {{"model", s.model}, {"params_si", p}};
      if (s.sweep) params[s.name]["sweep"] = {{"param", s.sweep->param}, {"values_si", s.sweep->values}};
    }
    attr_string(file, "parameters", params.dump());
    json checks = json::array();
    for (const auto& c : result.checks) checks.push_back(check_to_json(c));
    attr_string(file, "checks", checks.dump());

    H5Id series_group(make_group(file, "series"), H5Gclose);
    for (const auto& s : result.series) {
      H5Id g(make_group(series_group, s.name), H5Gclose);
      attr_string(g, "model", s.model);
      std::string notes;
      for (const auto& n : s.notes) notes += n + "\n";
      attr_string(g, "notes", notes);
      if (!s.error.empty()) attr_string(g, "error", s.error);
      write_columns(g, s.table);
      for (std::size_t k = 0; k < s.runs.size(); ++k) {
        const RunOutput& run = s.runs[k];
        H5Id pg(make_group(g, "point_" + std::to_string(k)), H5Gclose);
        std::string run_notes;
        for (const auto& n : run.notes) run_notes += n + "\n";
        attr_string(pg, "notes", run_notes);
        for (const auto& t : run.tables) write_table(pg, t);
        if (!run.snapshots.empty()) {
          H5Id sg(make_group(pg, "snapshots"), H5Gclose);
          for (std::size_t j = 0; j < run.snapshots.size(); ++j) {
            const Snapshot& snap = run.snapshots[j];
            const std::string name = std::to_string(j);
            H5Id one(make_group(sg, name), H5Gclose);
            attr_double(one, "time", snap.time);
            std::vector<double> xy(2 * snap.x.size());
            for (std::size_t i = 0; i < snap.x.size(); ++i) {
              xy[2 * i] = snap.x[i];
              xy[2 * i + 1] = snap.y[i];
            }
            dataset(one, "x", snap.x, "m");
            dataset(one, "y", snap.y, "m");
            {
              hsize_t dims[2] = {snap.x.size(), 2};
              H5Id space(H5Screate_simple(2, dims, nullptr), H5Sclose);
              H5Id ds(H5Dcreate2(one, "xy", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose);
              if (!xy.empty()) H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, xy.data());
              attr_string(ds, "units", "m");
            }
            for (const auto& f : snap.order) dataset(one, f, snap.fields.at(f), snap.units.at(f));
            const std::size_t nc = snap.num_cells();
            if (!snap.cells.empty()) {
              write_cells(one, snap);
              H5Id cg(make_group(one, "cell_fields"), H5Gclose);
              std::string order;
              for (const auto& f : snap.cell_order) {
                dataset(cg, f, snap.cell_fields.at(f), snap.cell_units.at(f));
                order += (order.empty() ? "" : ",") + f;
              }
              attr_string(cg, "columns", order);
            }
            // XDMF grid for ParaView: polyvertex points with attributes, or the triangles with
            // node and cell attributes when the snapshot has a mesh
            const std::string base = xml_escape(final_path.filename().string() + ":/series/" + s.name + "/point_" +
                                                std::to_string(k) + "/snapshots/" + name);
            const std::size_t n = snap.x.size();
            xdmf << "      <Grid Name=\"" << xml_escape(s.name + "_" + std::to_string(k) + "_" + name)
                 << "\" GridType=\"Uniform\">\n"
                 << "        <Time Value=\"" << snap.time << "\"/>\n";
            if (nc > 0) {
              xdmf << "        <Topology TopologyType=\"Triangle\" NumberOfElements=\"" << nc << "\"><DataItem Dimensions=\""
                   << nc << " 3\" Format=\"HDF\" NumberType=\"Int\" Precision=\"8\">" << base
                   << "/cells</DataItem></Topology>\n";
            } else {
              xdmf << "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n << "\"/>\n";
            }
            xdmf << "        <Geometry GeometryType=\"XY\"><DataItem Dimensions=\"" << n
                 << " 2\" Format=\"HDF\" NumberType=\"Float\" Precision=\"8\">" << base << "/xy</DataItem></Geometry>\n";
            for (const auto& f : snap.order) {
              xdmf << "        <Attribute Name=\"" << xml_escape(f) << "\" Center=\"Node\"><DataItem Dimensions=\"" << n
                   << "\" Format=\"HDF\" NumberType=\"Float\" Precision=\"8\">" << base << "/" << xml_escape(f)
                   << "</DataItem></Attribute>\n";
            }
            for (const auto& f : snap.cell_order) {
              xdmf << "        <Attribute Name=\"" << xml_escape(f) << "\" Center=\"Cell\"><DataItem Dimensions=\"" << nc
                   << "\" Format=\"HDF\" NumberType=\"Float\" Precision=\"8\">" << base << "/cell_fields/" << xml_escape(f)
                   << "</DataItem></Attribute>\n";
            }
            xdmf << "      </Grid>\n";
            have_snapshots = true;
          }
        }
      }
    }
  }
  fs::rename(tmp, final_path);
  if (have_snapshots) {
    std::ostringstream doc;
    doc << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n"
        << "    <Grid Name=\"snapshots\" GridType=\"Collection\" CollectionType=\"Temporal\">\n"
        << xdmf.str() << "    </Grid>\n  </Domain>\n</Xdmf>\n";
    write_atomic(dir / (spec.item_id + ".xdmf"), doc.str());
  }
  return final_path;
}

}  // namespace cutbench::framework
