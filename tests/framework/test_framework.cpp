#define BOOST_TEST_MODULE framework
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <thread>

#include <unistd.h>

#include "cutbench/common/checkpoint.hpp"
#include "cutbench/common/errors.hpp"
#include "cutbench/common/glossary.hpp"
#include "cutbench/framework/case.hpp"
#include "cutbench/framework/reference.hpp"
#include "cutbench/framework/run_cache.hpp"
#include "cutbench/framework/runner.hpp"
#include "cutbench/framework/store.hpp"

#include <hdf5.h>

namespace fs = std::filesystem;
using namespace cutbench;
using namespace cutbench::framework;

namespace {
struct Registered {
  Registered() { register_all(); }
};
BOOST_TEST_GLOBAL_FIXTURE(Registered);

// A toy model: y = a * x (+ not applicable for x < 0), to exercise series and checks.
void add_toy() {
  if (ModelRegistry::instance().find("toy_linear")) return;
  ModelSpec m;
  m.name = "toy_linear";
  m.description = "y = a x";
  m.source = "test";
  auto x = param("x", Dim::length, "abscissa");
  auto a = param("a", Dim::dimensionless, "slope");
  a.default_value = 2.0;
  m.params = {x, a};
  m.outputs = {{"y", Dim::length, "a x"}};
  m.evaluate = [](const Values& v) {
    ModelResult r;
    if (v.at("x") < 0) {
      r.applicable = false;
      r.note = "x < 0";
      return r;
    }
    r.outputs["y"] = v.at("a") * v.at("x");
    return r;
  };
  ModelRegistry::instance().add(m);
}

fs::path write_case(const std::string& name, const std::string& body, const std::string& tiers = "[\"quick\"]") {
  const fs::path dir = fs::temp_directory_path() / "cutbench_test_cases" / "nairn2015";
  fs::create_directories(dir);
  const fs::path file = dir / (name + ".toml");
  std::ofstream(file) << "id = \"nairn2015/" << name << "\"\npaper = \"nairn2015\"\nitem = \"Test\"\n"
                      << "title = \"t\"\nrequirement = \"r\"\nsolver = \"analytic\"\nmodels = [\"toy_linear\"]\n"
                      << "tiers = " << tiers << "\n" << body;
  return file;
}

// A quick-tier case file of one solver model (the preamble of the solver-run tests).
fs::path write_solver_case(const std::string& name, const std::string& model, const std::string& body) {
  const fs::path dir = fs::temp_directory_path() / "cutbench_test_cases" / "nairn2015";
  fs::create_directories(dir);
  const fs::path file = dir / (name + ".toml");
  std::ofstream(file) << "id = \"nairn2015/" << name << "\"\npaper = \"nairn2015\"\nitem = \"Test\"\n"
                      << "title = \"t\"\nrequirement = \"r\"\nsolver = \"mpm\"\nmodels = [\"" << model << "\"]\n"
                      << "tiers = [\"quick\"]\nstatus = \"implemented\"\n" << body;
  return file;
}
}  // namespace

BOOST_AUTO_TEST_CASE(every_inventory_item_has_a_case_file) {
  const fs::path root = source_root();
  std::set<std::string> listed;
  std::size_t n = 0;
  // the papers come from reference_data/*/inventory; every benchmarks/ directory of case files is one
  BOOST_TEST(paper_ids().size() == 5u);
  for (const auto& e : fs::directory_iterator(root / "benchmarks")) {
    bool has_cases = false;
    if (e.is_directory()) {
      for (const auto& f : fs::directory_iterator(e.path())) has_cases = has_cases || f.path().extension() == ".toml";
    }
    if (has_cases) BOOST_TEST(is_paper_id(e.path().filename().string()), e.path().filename().string());
  }
  for (const auto& paper : paper_ids()) {
    const Inventory inv = load_inventory(root, paper);
    BOOST_TEST_CONTEXT("paper " << paper) {
      BOOST_TEST(!inv.items.empty());
      BOOST_TEST(inv.meta.count("doi") == 1u);
      BOOST_TEST(inv.meta.count("citation") == 1u);
    }
    for (const auto& item : inv.items) {
      const fs::path file = root / "benchmarks" / paper / (item.id + ".toml");
      BOOST_TEST_CONTEXT(paper << "/" << item.id) {
        BOOST_TEST(fs::exists(file));
        if (fs::exists(file)) {
          CaseSpec c = load_case(file, "quick");
          BOOST_TEST(c.id == paper + "/" + item.id);
        }
      }
      listed.insert(paper + "/" + item.id);
      ++n;
    }
  }
  BOOST_TEST(n >= 55u);
  // And no case file outside the inventory.
  for (const auto& f : discover_case_files(root)) {
    const std::string id = f.parent_path().filename().string() + "/" + f.stem().string();
    BOOST_TEST_CONTEXT(id) { BOOST_TEST(listed.count(id) == 1u); }
  }
}

BOOST_AUTO_TEST_CASE(every_case_file_loads_in_both_tiers) {
  for (const auto& f : discover_case_files(source_root())) {
    BOOST_TEST_CONTEXT(f.string()) {
      BOOST_CHECK_NO_THROW(load_case(f, "quick"));
      BOOST_CHECK_NO_THROW(load_case(f, "full"));
    }
  }
}

BOOST_AUTO_TEST_CASE(reference_csv_units_and_selection) {
  const auto t = load_reference(source_root() / "reference_data/figueiredo2024/table1.csv", "test");
  BOOST_TEST(t.meta.count("doi") == 1u);
  const auto rows = t.select({{"t1", "0.5"}});
  BOOST_REQUIRE(rows.size() == 1u);
  BOOST_TEST(t.si_value("t1", rows[0]) == 0.5e-3, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(t.si_value("phi_exp", rows[0]) == 32.9 * 3.14159265358979323846 / 180, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(t.si_value("k", rows[0]) == 643.9e6, boost::test_tools::tolerance(1e-12));
  BOOST_CHECK_THROW(t.column("nope"), InputError);
  BOOST_CHECK_THROW(load_reference(source_root() / "reference_data/none.csv", "f"), InputError);
}

BOOST_AUTO_TEST_CASE(checks_metrics_and_statuses) {
  add_toy();
  const fs::path f = write_case("toy_checks", R"(status = "implemented"
[[series]]
name = "line"
model = "toy_linear"
params = { a = 3 }
sweep = { param = "x", from = "0 mm", to = "10 mm", n = 11 }

[[series]]
name = "neg"
model = "toy_linear"
params = { x = "-1 mm" }

[[checks]]
key = "at"
kind = "verification"
metric = "relative"
value = { series = "line", output = "y", at = { x = "2.5 mm" } }
reference = "7.5 mm"
tolerance = 1e-12
units = "mm"
source = "exact"

[[checks]]
key = "abs_fail"
kind = "verification"
metric = "absolute"
value = { series = "line", output = "y", reduce = "max" }
reference = 29
tolerance = "0.5 mm"
units = "mm"
source = "exact: 30 mm"

[[checks]]
key = "known"
kind = "reproduction"
metric = "absolute"
value = { series = "line", output = "y", row = 1 }
reference = 5
tolerance = 0.1
units = "mm"
source = "deliberately wrong"
tolerance_source = "test"
known_failure = { quick = "documented paper inconsistency" }
finding = "F01"

[[checks]]
key = "slope"
kind = "verification"
metric = "feature"
value = { series = "line", output = "y", x = "x", feature = "slope" }
reference = 3
tolerance = 1e-9
units = "1"
source = "exact"

[[checks]]
key = "range"
kind = "verification"
metric = "within"
value = { ratio = [ { series = "line", output = "y", row = 2 }, { series = "line", output = "x", row = 2 } ] }
reference = [2.9, 3.1]
units = "1"
source = "exact"

[[checks]]
key = "not_applicable"
kind = "verification"
metric = "absolute"
value = { series = "neg", output = "y" }
reference = 0
tolerance = 1
units = "mm"
source = "x < 0 has no solution"

[[checks]]
key = "ref_row_from_end"
kind = "verification"
metric = "absolute"
value = { series = "line", output = "y", at = { x = "0.3 mm" } }
reference = { file = "fig03.csv", column = "h", row = -1 }
tolerance = 1e-9
units = "mm"
source = "last row of nairn2015/fig03.csv: h = 0.9 mm"

[[series]]
name = "down"
model = "toy_linear"
params = { a = -3 }
sweep = { param = "x", from = "0 mm", to = "10 mm", n = 11 }

[[checks]]
key = "max_abs"
kind = "verification"
metric = "absolute"
value = { series = "down", output = "y", reduce = "max_abs" }
reference = 30
tolerance = 1e-9
units = "mm"
source = "exact: |y| = 3 x reaches 30 mm at x = 10 mm while max(y) = 0"

[[checks]]
key = "curve"
kind = "verification"
metric = "curve_max_norm"
value = { series = "line", output = "y", x = "x" }
reference = { series = "line", output = "y", x = "x" }
tolerance = { absolute = "1e-9 mm" }
units = "mm"
source = "identity"
)");
  CaseSpec c = load_case(f, "quick");
  CaseResult r = run_case(c, "quick", nullptr);
  std::map<std::string, std::string> st;
  for (const auto& ch : r.checks) st[ch.key] = ch.status;
  BOOST_TEST(st["at"] == "PASS");
  BOOST_TEST(st["abs_fail"] == "FAIL");
  BOOST_TEST(st["known"] == "FAIL");
  BOOST_TEST(st["slope"] == "PASS");
  BOOST_TEST(st["range"] == "PASS");
  BOOST_TEST(st["not_applicable"] == "NOT RUN");
  BOOST_TEST(st["curve"] == "PASS");
  BOOST_TEST(st["ref_row_from_end"] == "PASS");  // negative rows count from the end
  BOOST_TEST(st["max_abs"] == "PASS");           // the largest magnitude of a negative series
  BOOST_TEST(r.status == "FAIL");  // abs_fail is not a known failure
  const fs::path bad = write_case("toy_bad_row", R"(status = "implemented"
[[series]]
name = "line"
model = "toy_linear"
params = { x = "1 mm" }
[[checks]]
key = "row_out_of_range"
kind = "verification"
metric = "absolute"
value = { series = "line", output = "y" }
reference = { file = "fig03.csv", column = "h", row = -9 }
tolerance = 1e-9
units = "mm"
source = "test"
)");
  const CaseSpec cb = load_case(bad, "quick");
  BOOST_CHECK_EXCEPTION(run_case(cb, "quick", nullptr), InputError,
                        [](const InputError& e) { return e.field().find(".row") != std::string::npos; });
}

BOOST_AUTO_TEST_CASE(known_failure_can_name_its_tier) {
  add_toy();
  // y = 2 x = 2 mm against 5 mm: fails on both tiers, documented for the full tier only
  const std::string check = R"(status = "implemented"
[[series]]
name = "line"
model = "toy_linear"
params = { x = "1 mm" }
[[checks]]
key = "k"
kind = "reproduction"
metric = "absolute"
value = { series = "line", output = "y" }
reference = 5
tolerance = 0.1
units = "mm"
source = "deliberately wrong"
tolerance_source = "test"
finding = "F01"
)";
  const fs::path f = write_case("toy_kf_tier", check + "known_failure = { full = \"full-tier reason\" }\n", "[\"quick\", \"full\"]");
  const CaseResult quick = run_case(load_case(f, "quick"), "quick", nullptr);
  const CaseResult full = run_case(load_case(f, "full"), "full", nullptr);
  BOOST_REQUIRE_EQUAL(quick.checks.size(), 1u);
  BOOST_REQUIRE_EQUAL(full.checks.size(), 1u);
  BOOST_TEST(quick.checks[0].status == "FAIL");
  BOOST_TEST(quick.checks[0].known_failure.empty());  // undocumented on the quick tier: an unexpected failure
  BOOST_TEST(full.checks[0].status == "FAIL");
  BOOST_TEST(full.checks[0].known_failure == "full-tier reason");
  const fs::path bad = write_case("toy_kf_bad_tier", check + "known_failure = { slow = \"x\" }\n", "[\"quick\", \"full\"]");
  BOOST_CHECK_EXCEPTION(load_case(bad, "quick"), InputError,
                        [](const InputError& e) { return e.field().find("known_failure.slow") != std::string::npos; });
}

BOOST_AUTO_TEST_CASE(bad_case_files_name_the_field) {
  add_toy();
  auto expect_field = [](const std::string& name, const std::string& body, const std::string& field_part) {
    const fs::path f = write_case(name, body);
    try {
      load_case(f, "quick");
      BOOST_ERROR("no error for " << name);
    } catch (const InputError& e) {
      BOOST_TEST_CONTEXT(name << ": " << e.what()) {
        BOOST_TEST(std::string(e.what()).find(field_part) != std::string::npos);
      }
    }
  };
  expect_field("bad_key", "status = \"implemented\"\ncolour = 3\n", "colour");
  expect_field("bad_unit", "status = \"implemented\"\n[[series]]\nname = \"s\"\nmodel = \"toy_linear\"\nparams = { x = \"2 MPa\" }\n",
               "params.x");
  expect_field("bad_model", "status = \"implemented\"\n[[series]]\nname = \"s\"\nmodel = \"nope\"\n", "model");
  expect_field("bad_status", "status = \"maybe\"\n", "status");
  expect_field("bad_ref", "status = \"implemented\"\n[[checks]]\nkey = \"k\"\nkind = \"verification\"\nmetric = \"relative\"\n"
               "value = { series = \"s\", output = \"y\" }\nreference = { file = \"missing.csv\", column = \"x\" }\ntolerance = 0.1\n"
               "units = \"1\"\nsource = \"s\"\n",
               "reference.file");
  const std::string check = "status = \"implemented\"\n[[checks]]\nkey = \"k\"\nkind = \"reproduction\"\nmetric = \"relative\"\n"
                            "value = { series = \"s\", output = \"y\" }\nreference = 1\nunits = \"1\"\nsource = \"s\"\n";
  expect_field("literal_value", "status = \"implemented\"\n[[checks]]\nkey = \"k\"\nkind = \"consistency\"\n"
               "metric = \"relative\"\nvalue = 1\nreference = 1\ntolerance = 0.1\nunits = \"1\"\nsource = \"s\"\n",
               "value");
  expect_field("tolerance_text", check + "tolerance_source = \"t\"\ntolerance = \"abc\"\n", "tolerance");
  expect_field("tolerance_huge", check + "tolerance_source = \"t\"\ntolerance = 1e300\n", "tolerance");
  expect_field("tolerance_inf", check + "tolerance_source = \"t\"\ntolerance = inf\n", "tolerance");
  expect_field("no_tolerance_source", check + "tolerance = 0.1\n", "tolerance_source");
  expect_field("known_failure_plain", check + "tolerance_source = \"t\"\ntolerance = 0.1\nknown_failure = \"x\"\nfinding = \"F01\"\n",
               "known_failure");
  expect_field("finding_missing", check + "tolerance_source = \"t\"\ntolerance = 0.1\nknown_failure = { quick = \"x\" }\n",
               "finding");
  expect_field("sweep_n_text", "status = \"implemented\"\n[[series]]\nname = \"s\"\nmodel = \"toy_linear\"\n"
               "sweep = { param = \"x\", from = \"0 mm\", to = \"1 mm\", n = \"300\" }\n", "sweep.n");
  expect_field("sweep_n_fraction", "status = \"implemented\"\n[[series]]\nname = \"s\"\nmodel = \"toy_linear\"\n"
               "sweep = { param = \"x\", from = \"0 mm\", to = \"1 mm\", n = 2.5 }\n", "sweep.n");
  expect_field("series_name_slash", "status = \"implemented\"\n[[series]]\nname = \"a/b\"\nmodel = \"toy_linear\"\n"
               "params = { x = \"1 mm\" }\n", "name");
  expect_field("series_name_twice", "status = \"implemented\"\n[[series]]\nname = \"s\"\nmodel = \"toy_linear\"\n"
               "params = { x = \"1 mm\" }\n[[series]]\nname = \"s\"\nmodel = \"toy_linear\"\nparams = { x = \"2 mm\" }\n",
               "name");
}

BOOST_AUTO_TEST_CASE(hdf5_result_has_provenance_and_units) {
  add_toy();
  const fs::path f = write_case("toy_h5", R"(status = "implemented"
[[series]]
name = "line"
model = "toy_linear"
sweep = { param = "x", values = ["1 mm", "2 mm"] }
)");
  CaseSpec c = load_case(f, "quick");
  CaseResult r = run_case(c, "quick", nullptr);
  const fs::path out = fs::temp_directory_path() / "cutbench_test_results";
  fs::remove_all(out);
  const fs::path h5 = write_hdf5(c, r, out);
  write_case_json(out, c, r);
  BOOST_TEST(fs::exists(h5));
  for (const auto& e : fs::recursive_directory_iterator(out)) {
    BOOST_TEST(e.path().string().find(".tmp") == std::string::npos);  // temp files renamed
  }
  const hid_t file = H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  BOOST_REQUIRE(file >= 0);
  for (const char* a : {"software_version", "date", "case_id", "paper_doi", "item", "parameters", "threads",
                        "wall_time_s", "checks"}) {
    BOOST_TEST_CONTEXT(a) { BOOST_TEST(H5Aexists(file, a) > 0); }
  }
  for (const char* d : {"/series/line/x", "/series/line/y", "/series/line/applicable"}) {
    const hid_t ds = H5Dopen2(file, d, H5P_DEFAULT);
    BOOST_TEST_CONTEXT(d) {
      BOOST_REQUIRE(ds >= 0);
      BOOST_TEST(H5Aexists(ds, "units") > 0);
    }
    H5Dclose(ds);
  }
  double y[2] = {0, 0};
  const hid_t ds = H5Dopen2(file, "/series/line/y", H5P_DEFAULT);
  H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, y);
  H5Dclose(ds);
  H5Fclose(file);
  BOOST_TEST(y[0] == 2e-3, boost::test_tools::tolerance(1e-14));  // a = 2 default, x = 1 mm
  BOOST_TEST(y[1] == 4e-3, boost::test_tools::tolerance(1e-14));
  const json j = read_case_json(out, c);
  BOOST_TEST(j["status"].get<std::string>() == "NOT RUN");  // no checks
}

namespace {
// A snapshot with a mesh: two triangles on four points, one point field and two cell fields.
Snapshot mesh_snapshot() {
  Snapshot snap;
  snap.time = 0.5;
  snap.x = {0.0, 1.0, 1.0, 0.0};
  snap.y = {0.0, 0.0, 1.0, 1.0};
  snap.add("v_x", "m/s", {0.0, 1.0, 2.0, 1.0 / 3.0});
  snap.cells = {0, 1, 2, 0, 2, 3};
  snap.add_cell_field("dissipation_density", "1", {0.125, 1.0 / 7.0});
  snap.add_cell_field("element", "1", {4.0, 4.0});
  return snap;
}

std::vector<hsize_t> h5_dims(hid_t file, const std::string& path) {
  const hid_t ds = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  if (ds < 0) return {};
  const hid_t sp = H5Dget_space(ds);
  std::vector<hsize_t> d(static_cast<std::size_t>(H5Sget_simple_extent_ndims(sp)));
  H5Sget_simple_extent_dims(sp, d.data(), nullptr);
  H5Sclose(sp);
  H5Dclose(ds);
  return d;
}
}  // namespace

BOOST_AUTO_TEST_CASE(hdf5_snapshot_with_cells_is_a_triangle_mesh) {
  add_toy();
  const fs::path f = write_case("toy_mesh", R"(status = "implemented"
[[series]]
name = "line"
model = "toy_linear"
sweep = { param = "x", values = ["1 mm"] }
)");
  CaseSpec c = load_case(f, "quick");
  CaseResult r = run_case(c, "quick", nullptr);
  RunOutput run;
  run.snapshots.push_back(mesh_snapshot());
  Snapshot cloud;  // a particle snapshot next to it stays a point cloud
  cloud.x = {0.5};
  cloud.y = {0.5};
  cloud.add("T", "K", {300.0});
  run.snapshots.push_back(cloud);
  r.series[0].runs = {run};
  const fs::path out = fs::temp_directory_path() / "cutbench_test_mesh_results";
  fs::remove_all(out);
  const fs::path h5 = write_hdf5(c, r, out);
  const hid_t file = H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  BOOST_REQUIRE(file >= 0);
  const std::string g = "/series/line/point_0/snapshots/";
  BOOST_TEST((h5_dims(file, g + "0/cells") == std::vector<hsize_t>{2, 3}));
  BOOST_TEST((h5_dims(file, g + "0/xy") == std::vector<hsize_t>{4, 2}));
  BOOST_TEST((h5_dims(file, g + "0/v_x") == std::vector<hsize_t>{4}));
  BOOST_TEST((h5_dims(file, g + "0/cell_fields/dissipation_density") == std::vector<hsize_t>{2}));
  BOOST_TEST((h5_dims(file, g + "0/cell_fields/element") == std::vector<hsize_t>{2}));
  BOOST_TEST(h5_dims(file, g + "1/cells").empty());  // no mesh, no connectivity
  {
    long long cells[6] = {};
    const hid_t ds = H5Dopen2(file, (g + "0/cells").c_str(), H5P_DEFAULT);
    H5Dread(ds, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, cells);
    H5Dclose(ds);
    BOOST_TEST((std::vector<long long>(cells, cells + 6) == std::vector<long long>{0, 1, 2, 0, 2, 3}));
    double d[2] = {};
    const hid_t df = H5Dopen2(file, (g + "0/cell_fields/dissipation_density").c_str(), H5P_DEFAULT);
    BOOST_TEST(H5Aexists(df, "units") > 0);
    H5Dread(df, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, d);
    H5Dclose(df);
    BOOST_TEST(d[1] == 1.0 / 7.0);  // bit-exact
  }
  H5Fclose(file);
  std::ifstream in(out / "nairn2015" / "toy_mesh.xdmf");
  const std::string xdmf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  BOOST_TEST(xdmf.find("TopologyType=\"Triangle\" NumberOfElements=\"2\"") != std::string::npos);
  BOOST_TEST(xdmf.find("Dimensions=\"2 3\" Format=\"HDF\" NumberType=\"Int\"") != std::string::npos);
  BOOST_TEST(xdmf.find("/point_0/snapshots/0/cells<") != std::string::npos);
  BOOST_TEST(xdmf.find("Name=\"v_x\" Center=\"Node\"") != std::string::npos);
  BOOST_TEST(xdmf.find("Name=\"dissipation_density\" Center=\"Cell\"") != std::string::npos);
  BOOST_TEST(xdmf.find("/snapshots/0/cell_fields/dissipation_density<") != std::string::npos);
  BOOST_TEST(xdmf.find("TopologyType=\"Polyvertex\" NumberOfElements=\"1\"") != std::string::npos);  // the cloud

  // an inconsistent mesh is refused before anything is written
  Snapshot bad = mesh_snapshot();
  bad.cells[5] = 4;  // only 4 points
  r.series[0].runs[0].snapshots = {bad};
  fs::remove_all(out);
  BOOST_CHECK_THROW(write_hdf5(c, r, out), std::runtime_error);
  BOOST_TEST(!fs::exists(out / "nairn2015" / "toy_mesh.h5"));
  bad = mesh_snapshot();
  bad.cell_fields["element"].pop_back();
  r.series[0].runs[0].snapshots = {bad};
  BOOST_CHECK_THROW(write_hdf5(c, r, out), std::runtime_error);
}

BOOST_AUTO_TEST_CASE(run_cache_round_trip) {
  RunOutput run;
  Table t;
  t.name = "forces";
  t.add("t", "s", {0.0, 1e-6, 2e-6});
  t.add("F_c", "N/m", {1.5, -2.25, 3.125});
  run.tables.push_back(t);
  Snapshot snap;
  snap.time = 4e-6;
  snap.x = {0.0, 1.0};
  snap.y = {2.0, 3.0};
  snap.add("T", "K", {300.0, 1200.5});
  run.snapshots.push_back(snap);
  const Snapshot mesh = mesh_snapshot();
  run.snapshots.push_back(mesh);
  run.set_scalar("F_c", 1.0 / 3.0, "N/m");
  run.set_scalar("steps", 12345.0, "1");
  run.notes = {"a note", ""};
  const Values params{{"h", 1e-3}, {"mu", 0.35}};
  const std::string key = run_key("toy_solver", params);
  const fs::path dir = fs::temp_directory_path() / "cutbench_test_runcache";
  fs::remove_all(dir);
  const std::string path = (dir / run_file_name("toy_solver", key)).string();
  save_run(path, key, run);
  for (const auto& e : fs::directory_iterator(dir)) BOOST_TEST(e.path().extension() != ".tmp");  // renamed
  RunOutput back;
  BOOST_REQUIRE(load_run(path, key, back));
  BOOST_TEST(back.tables.size() == 1u);
  BOOST_TEST(back.tables[0].name == "forces");
  BOOST_TEST((back.tables[0].order == t.order));
  BOOST_TEST((back.tables[0].columns == t.columns));
  BOOST_TEST((back.tables[0].units == t.units));
  BOOST_REQUIRE(back.snapshots.size() == 2u);
  BOOST_TEST(back.snapshots[0].time == 4e-6);
  BOOST_TEST((back.snapshots[0].x == snap.x));
  BOOST_TEST((back.snapshots[0].fields == snap.fields));
  BOOST_TEST(back.snapshots[0].cells.empty());
  BOOST_TEST(back.snapshots[0].cell_fields.empty());
  const Snapshot& m = back.snapshots[1];  // the mesh, bit-exact
  BOOST_TEST((m.x == mesh.x));
  BOOST_TEST((m.y == mesh.y));
  BOOST_TEST((m.order == mesh.order));
  BOOST_TEST((m.fields == mesh.fields));
  BOOST_TEST((m.units == mesh.units));
  BOOST_TEST((m.cells == mesh.cells));
  BOOST_TEST((m.cell_order == mesh.cell_order));
  BOOST_TEST((m.cell_fields == mesh.cell_fields));
  BOOST_TEST((m.cell_units == mesh.cell_units));
  BOOST_TEST((back.scalars == run.scalars));  // bit-exact
  BOOST_TEST((back.scalar_units == run.scalar_units));
  BOOST_TEST((back.notes == run.notes));
  // another key (a parameter differs in the last digit) does not load; neither does a cut file
  Values other = params;
  other["mu"] = 0.35000000000000003;
  const std::string key2 = run_key("toy_solver", other);
  BOOST_TEST(key2 != key);
  BOOST_TEST(!load_run(path, key2, back));
  BOOST_TEST(!load_run((dir / "absent.run").string(), key, back));
  const auto size = fs::file_size(path);
  fs::resize_file(path, size - 5);
  BOOST_TEST(!load_run(path, key, back));
}

// Runs of the registered solvers are keyed by their method's source identity (not by the
// executable or the git commit), so that stored runs stay valid across builds and machines.
BOOST_AUTO_TEST_CASE(run_keys_use_the_solver_source_identity) {
  const auto is_identity = [](const std::string& id) {
    return id.size() == 64 && id.find_first_not_of("0123456789abcdef") == std::string::npos;
  };
  std::set<std::string> methods;
  for (const auto& s : SolverRegistry::instance().all()) {
    if (s.name.rfind("toy_", 0) == 0) continue;  // this file's own solvers
    const std::string id = solver_identity(s.name);
    BOOST_TEST_CONTEXT(s.name) {
      BOOST_TEST(is_identity(id));
      const std::string key = run_key(s.name, {{"a", 1.0}});
      BOOST_TEST(key == s.name + "|source " + id + "|a=1");
      BOOST_TEST(key.find(software_version()) == std::string::npos);
    }
    methods.insert(id);
  }
  // one identity per method: solvers of one library share it, libraries differ
  if (SolverRegistry::instance().find("sph_cutting") && SolverRegistry::instance().find("sph_heat")) {
    BOOST_TEST(solver_identity("sph_cutting") == solver_identity("sph_heat"));
  }
  if (SolverRegistry::instance().find("sph_cutting") && SolverRegistry::instance().find("efg_cutting")) {
    BOOST_TEST(solver_identity("sph_cutting") != solver_identity("efg_cutting"));
  }
  // a solver without an identity falls back to the version and the executable's hash
  BOOST_TEST(solver_identity("no_such_solver").empty());
  const std::string fallback = run_key("no_such_solver", {});
  BOOST_TEST(fallback.find("no_such_solver|" + software_version() + "|build ") == 0u);
}

// A run store is read without running anything: each file's solver, parameters and whether this
// build can use it.
BOOST_AUTO_TEST_CASE(run_store_scan_tells_current_from_stale) {
  const std::string id(64, 'a');
  set_solver_identity("toy_store_solver", id);
  const fs::path dir = fs::temp_directory_path() / "cutbench_test_runstore";
  fs::remove_all(dir);
  fs::create_directories(dir);
  RunOutput run;
  run.set_scalar("y", 2.0, "1");
  run.notes = {"run stored in the run cache: computed by a test"};
  const std::string current = run_key("toy_store_solver", {{"a", 1.5}, {"b", 2.0}});
  BOOST_TEST(current == "toy_store_solver|source " + id + "|a=1.5|b=2");
  save_run((dir / run_file_name("toy_store_solver", current)).string(), current, run);
  const std::string stale = "toy_store_solver|source " + std::string(64, 'b') + "|a=3";
  save_run((dir / "toy_store_solver-stale.run").string(), stale, run);
  const std::string old = "toy_store_solver|0.1.0+abc|build 0123456789abcdef|a=3";
  save_run((dir / "toy_store_solver-old.run").string(), old, run);
  const std::string unknown = "no_such_solver|source " + id + "|a=3";
  save_run((dir / "no_such_solver-x.run").string(), unknown, run);
  write_checkpoint(CheckpointSpec{(dir / "toy_store_solver-y.ckpt").string(), current, 1.0, false},
                   [](BinaryWriter& w) { w.f64(1.0); });
  std::ofstream(dir / "garbage.run") << "not a run";
  std::ofstream(dir / "README.md") << "ignored";
  const auto stored = scan_run_store(dir.string());
  std::map<std::string, StoredRun> by_file;
  for (const auto& s : stored) by_file[s.file] = s;
  BOOST_REQUIRE(stored.size() == 6u);
  const StoredRun& c = by_file.at(run_file_name("toy_store_solver", current));
  BOOST_TEST(c.state == "current");
  BOOST_TEST(c.kind == "run");
  BOOST_TEST(c.solver == "toy_store_solver");
  BOOST_TEST(c.identity == id);
  BOOST_TEST(c.params.at("a") == 1.5);
  BOOST_TEST(c.params.at("b") == 2.0);
  BOOST_TEST(c.provenance == "run stored in the run cache: computed by a test");
  BOOST_TEST(by_file.at("toy_store_solver-stale.run").state == "stale");
  BOOST_TEST(by_file.at("toy_store_solver-old.run").state == "executable-keyed");
  BOOST_TEST(by_file.at("toy_store_solver-old.run").params.at("a") == 3.0);
  BOOST_TEST(by_file.at("no_such_solver-x.run").state == "unknown solver");
  BOOST_TEST(by_file.at("toy_store_solver-y.ckpt").state == "current");
  BOOST_TEST(by_file.at("toy_store_solver-y.ckpt").kind == "checkpoint");
  BOOST_TEST(by_file.at("garbage.run").state == "unreadable");
  BOOST_CHECK_THROW(scan_run_store((dir / "absent").string()), InputError);
  fs::remove_all(dir);
}

BOOST_AUTO_TEST_CASE(run_cache_shares_and_resumes_solver_runs) {
  static int calls = 0;
  if (!SolverRegistry::instance().find("toy_counting_solver")) {
    SolverSpec sv;
    sv.name = "toy_counting_solver";
    sv.description = "counts its runs";
    sv.source = "test";
    sv.params = {param("a", Dim::dimensionless, "input", 1.0, 0.0, 10.0)};
    sv.scalars = {{"y", Dim::dimensionless, "2 a"}};
    sv.run = [](const Values& v, const ProgressFn&) {
      ++calls;
      RunOutput r;
      r.set_scalar("y", 2.0 * v.at("a"), "1");
      return r;
    };
    SolverRegistry::instance().add(sv);
  }
  const fs::path dir = fs::temp_directory_path() / "cutbench_test_cases" / "nairn2015";
  fs::create_directories(dir);
  const fs::path f = dir / "toy_cache.toml";
  std::ofstream(f) << R"(id = "nairn2015/toy_cache"
paper = "nairn2015"
item = "Test"
title = "t"
requirement = "r"
solver = "mpm"
models = ["toy_counting_solver"]
tiers = ["quick"]
status = "implemented"
[[series]]
name = "first"
model = "toy_counting_solver"
sweep = { param = "a", values = [1, 2] }
[[series]]
name = "same_as_first_point"
model = "toy_counting_solver"
params = { a = 1 }
)";
  const CaseSpec c = load_case(f, "quick");
  const fs::path cache = fs::temp_directory_path() / "cutbench_test_runcache2";
  fs::remove_all(cache);
  struct Reset {
    ~Reset() { set_run_cache_dir(""); }
  } reset;  // the cache is global: switch it off even if a check throws
  // a directory that cannot be created is an input error naming the option
  const fs::path blocker = fs::temp_directory_path() / "cutbench_test_runcache_file";
  std::ofstream(blocker) << "x";
  BOOST_CHECK_EXCEPTION(set_run_cache_dir((blocker / "sub").string()), InputError,
                        [](const InputError& e) { return e.field() == "--run-cache"; });
  fs::remove(blocker);
  calls = 0;
  const CaseResult plain = run_case(c, "quick", nullptr);  // cache off: every point runs
  BOOST_TEST(calls == 3);
  set_run_cache_dir(cache.string());
  calls = 0;
  const CaseResult first = run_case(c, "quick", nullptr);
  BOOST_TEST(calls == 2);  // the second series reuses the first point
  const CaseResult again = run_case(c, "quick", nullptr);
  BOOST_TEST(calls == 2);  // nothing recomputed
  set_run_cache_dir("");
  for (const auto* r : {&first, &again}) {
    BOOST_REQUIRE(r->series.size() == 2u);
    BOOST_TEST((r->series[0].table.columns.at("y") == plain.series[0].table.columns.at("y")));
    BOOST_TEST((r->series[1].table.columns.at("y") == plain.series[1].table.columns.at("y")));
  }
  // reuse is stated in the notes
  bool noted = false;
  for (const auto& n : again.series[0].notes) noted = noted || n.find("run cache") != std::string::npos;
  BOOST_TEST(noted);
  // the plan names the files the case wrote, without running anything
  calls = 0;
  const auto plan = planned_runs(c);
  BOOST_TEST(calls == 0);
  BOOST_REQUIRE(plan.size() == 3u);
  BOOST_TEST(plan[0].series == "first");
  BOOST_TEST(plan[1].point == 2u);
  BOOST_TEST(plan[1].params.at("a") == 2.0);
  BOOST_TEST(plan[2].file == plan[0].file);  // the shared run
  std::map<std::string, StoredRun> store;
  for (auto& st : scan_run_store(cache.string())) store[st.file] = st;
  for (const auto& p : plan) {
    BOOST_TEST(p.key == run_key("toy_counting_solver", p.params));
    BOOST_TEST(fs::exists(cache / p.file));
  }
  // the toy solver has no source identity: its runs are executable-keyed, so a store does not
  // count them as usable; with an identity they are stored, and a lone checkpoint resumes
  BOOST_TEST(planned_run_state(plan[0], store) == "to compute");
  set_solver_identity("toy_counting_solver", std::string(64, 'c'));
  const auto plan2 = planned_runs(c);
  RunOutput copy;
  BOOST_REQUIRE(load_run((cache / plan[0].file).string(), plan[0].key, copy));
  save_run((cache / plan2[0].file).string(), plan2[0].key, copy);
  write_checkpoint(CheckpointSpec{(cache / (plan2[1].file.substr(0, plan2[1].file.size() - 4) + ".ckpt")).string(),
                                  plan2[1].key, 1.0, false},
                   [](BinaryWriter& w) { w.f64(0.5); });
  store.clear();
  for (auto& st : scan_run_store(cache.string())) store[st.file] = st;
  BOOST_TEST(planned_run_state(plan2[0], store) == "stored");
  BOOST_TEST(planned_run_state(plan2[1], store) == "checkpoint");
  set_solver_identity("toy_counting_solver", "");
  fs::remove(f);
}

// The manifest that the report reads counts, per case and per paper, the distinct full-tier solver
// runs and how many of them the repository's run store holds (the campaign's progress).
BOOST_AUTO_TEST_CASE(manifest_counts_the_full_tier_runs) {
  if (!SolverRegistry::instance().find("sph_cutting")) return;  // solvers not in this build
  const fs::path dir = fs::temp_directory_path() / "cutbench_test_manifest";
  fs::remove_all(dir);
  fs::create_directories(dir);
  write_manifest(dir);
  std::ifstream in(dir / "manifest.json");
  const json m = json::parse(in);
  bool seen = false;
  int per_case_sum = 0;  // afrasiabi2021's runs counted once per case that uses them
  for (const auto& c : m.at("cases")) {
    if (c.at("case").get<std::string>().rfind("afrasiabi2021/", 0) == 0 && c.contains("full_runs"))
      per_case_sum += c.at("full_runs").at("total").get<int>();
    if (c.at("case") != "afrasiabi2021/fig06") continue;
    seen = true;
    BOOST_TEST(c.at("full_runs").at("total").get<int>() == 4);  // reference + enhanced at three mu
    BOOST_TEST(c.at("full_runs").at("stored").get<int>() <= 4);
  }
  BOOST_TEST(seen);
  // fig05 and fig07 share fig06's mu = 0.35 runs: the paper counts distinct runs
  const auto& fr = m.at("full_runs").at("afrasiabi2021");
  BOOST_TEST(fr.at("total").get<int>() >= 4);
  BOOST_TEST(fr.at("total").get<int>() < per_case_sum);
  fs::remove_all(dir);
}

// Recorded full-tier runs (reports/full_tier/<paper>/<item>.json, written by
// reports/record_full_tier.py) are shown in the report next to the quick tier: each must name an
// existing case and only checks that case evaluates in the full tier, say how it was run, and
// carry the tolerance the case file states now (a tolerance changed after recording would
// otherwise show a stale status).
BOOST_AUTO_TEST_CASE(recorded_full_tier_runs_match_their_case_files) {
  const fs::path dir = source_root() / "reports" / "full_tier";
  if (!fs::is_directory(dir)) return;
  int records = 0;
  for (const auto& paper : fs::directory_iterator(dir)) {
    if (!paper.is_directory()) continue;
    for (const auto& f : fs::directory_iterator(paper.path())) {
      if (f.path().extension() != ".json") continue;
      BOOST_TEST_CONTEXT(f.path().string()) {
        std::ifstream in(f.path());
        const json rec = json::parse(in);
        ++records;
        const std::string id = rec.at("case").get<std::string>();
        BOOST_TEST(id == paper.path().filename().string() + "/" + f.path().stem().string());
        BOOST_TEST(rec.at("tier").get<std::string>() == "full");
        BOOST_TEST(rec.at("recorded").at("how").get<std::string>().size() >= 10u);
        const CaseSpec cs = load_case(resolve_case(id, source_root()), "full");
        BOOST_TEST(cs.in_tier("full"));
        for (const auto& ch : rec.at("checks")) {
          const std::string key = ch.at("key").get<std::string>();
          BOOST_TEST_CONTEXT(key) {
            const CheckSpec* spec = nullptr;
            for (const auto& c : cs.checks)
              if (c.key == key && (c.tiers.empty() || std::count(c.tiers.begin(), c.tiers.end(), "full")))
                spec = &c;
            BOOST_TEST_REQUIRE(spec != nullptr);
            BOOST_TEST(ch.at("status").get<std::string>() != "");
            if (spec->tolerance.is_number() && ch.contains("tolerance") && ch.at("tolerance").is_number())
              BOOST_TEST(ch.at("tolerance").get<double>() == spec->tolerance.get<double>(),
                         boost::test_tools::tolerance(1e-12));
          }
        }
      }
    }
  }
  BOOST_TEST_MESSAGE(records << " recorded full-tier case runs checked");
}

// A series that throws makes its checks ERROR and the case ERROR, never NOT RUN or PASS.
BOOST_AUTO_TEST_CASE(a_series_that_throws_is_an_error) {
  add_toy();
  if (!ModelRegistry::instance().find("toy_throws")) {
    ModelSpec m;
    m.name = "toy_throws";
    m.description = "throws";
    m.source = "test";
    m.params = {param("x", Dim::length, "abscissa")};
    m.outputs = {{"y", Dim::length, "never"}};
    m.evaluate = [](const Values&) -> ModelResult { throw std::runtime_error("out of memory (simulated)"); };
    ModelRegistry::instance().add(m);
  }
  const fs::path f = write_case("toy_error", R"(status = "implemented"
[[series]]
name = "bad"
model = "toy_throws"
params = { x = "1 mm" }
[[series]]
name = "good"
model = "toy_linear"
params = { x = "1 mm" }
[[checks]]
key = "reads_bad"
kind = "verification"
metric = "absolute"
value = { series = "bad", output = "y" }
reference = 2
tolerance = 0.1
units = "mm"
source = "test"
[[checks]]
key = "reads_good"
kind = "verification"
metric = "absolute"
value = { series = "good", output = "y" }
reference = 2
tolerance = 0.1
units = "mm"
source = "test"
)");
  const CaseResult r = run_case(load_case(f, "quick"), "quick", nullptr);
  BOOST_TEST(r.checks[0].status == "ERROR");
  BOOST_TEST(r.checks[0].message.find("out of memory") != std::string::npos);
  BOOST_TEST(r.checks[1].status == "PASS");
  BOOST_TEST(r.status == "ERROR");
}

// A solver output that is not finite at every selected point (a stick zone that does not form, a
// serration that is not there) is a FAIL: the run did not produce what the paper reports. Where the
// solver defines the output at some of the points, those are used.
BOOST_AUTO_TEST_CASE(a_solver_output_left_undefined_fails) {
  if (!SolverRegistry::instance().find("toy_nan_solver")) {
    SolverSpec sv;
    sv.name = "toy_nan_solver";
    sv.description = "y = a, undefined above 5";
    sv.source = "test";
    sv.params = {param("a", Dim::dimensionless, "input", 1.0, 0.0, 10.0)};
    sv.scalars = {{"y", Dim::dimensionless, "a, NaN for a > 5"}};
    sv.run = [](const Values& v, const ProgressFn&) {
      RunOutput r;
      const double a = v.at("a");
      r.set_scalar("y", a > 5.0 ? std::numeric_limits<double>::quiet_NaN() : a, "1");
      return r;
    };
    SolverRegistry::instance().add(sv);
  }
  const fs::path f = write_case("toy_nan", R"(status = "implemented"
[[series]]
name = "undefined"
model = "toy_nan_solver"
params = { a = 6 }
[[series]]
name = "partly"
model = "toy_nan_solver"
sweep = { param = "a", values = [2, 7] }
[[checks]]
key = "reads_undefined"
kind = "reproduction"
metric = "absolute"
value = { series = "undefined", output = "y" }
reference = 6
tolerance = 0.1
units = "1"
source = "test"
tolerance_source = "test"
[[checks]]
key = "reads_the_defined_point"
kind = "reproduction"
metric = "absolute"
value = { series = "partly", output = "y", reduce = "max" }
reference = 2
tolerance = 0.1
units = "1"
source = "test"
tolerance_source = "test"
)");
  const CaseResult r = run_case(load_case(f, "quick"), "quick", nullptr);
  BOOST_TEST(r.checks[0].status == "FAIL");
  BOOST_TEST(r.checks[0].message.find("does not define 'y'") != std::string::npos);
  BOOST_TEST(r.checks[1].status == "PASS");
}

// A value within the measured scatter of a boundary is INCONCLUSIVE; outside it the verdict stands.
// A bare scatter number is in the check's units.
BOOST_AUTO_TEST_CASE(scatter_makes_a_close_call_inconclusive) {
  add_toy();
  auto run_with = [](const std::string& name, const std::string& reference, const std::string& scatter) {
    const fs::path f = write_case(name, R"(status = "implemented"
[[series]]
name = "line"
model = "toy_linear"
params = { x = "1 mm" }
[[checks]]
key = "k"
kind = "reproduction"
metric = "absolute"
value = { series = "line", output = "y" }
reference = )" + reference + R"(
tolerance = 0.5
units = "mm"
source = "test"
tolerance_source = "test"
scatter = )" + scatter + R"(
scatter_source = "test"
)");
    return run_case(load_case(f, "quick"), "quick", nullptr).checks[0];
  };
  // y = 2 mm; boundary at 2.4 mm (reference 2.9): 0.4 mm from it
  BOOST_TEST(run_with("toy_sc1", "2.9", "0.5").status == "INCONCLUSIVE");
  BOOST_TEST(run_with("toy_sc2", "2.9", "0.3").status == "FAIL");
  BOOST_TEST(run_with("toy_sc3", "2.0", "0.3").status == "PASS");
  BOOST_TEST(run_with("toy_sc4", "2.0", "\"0.6 mm\"").status == "INCONCLUSIVE");
  BOOST_TEST(run_with("toy_sc5", "2.0", "{ full = 0.6 }").status == "PASS");  // no quick-tier scatter
}

// Run histories: a window given as fractions of the x range, the drift between its two halves, and
// one number across every run of a series (run = "each").
BOOST_AUTO_TEST_CASE(drift_over_a_window_fraction_across_runs) {
  if (!SolverRegistry::instance().find("toy_history_solver")) {
    SolverSpec sv;
    sv.name = "toy_history_solver";
    sv.description = "f(t) = 1 + a t on t = 0, 1, ..., 10";
    sv.source = "test";
    sv.params = {param("a", Dim::dimensionless, "slope", 0.0, -1.0, 1.0)};
    sv.scalars = {{"f_end", Dim::dimensionless, "f(10)"}};
    sv.tables = {{"hist", "history", {{"t", "1", "time"}, {"f", "1", "value"}}}};
    sv.run = [](const Values& v, const ProgressFn&) {
      RunOutput r;
      Table h;
      h.name = "hist";
      std::vector<double> ts, fs_;
      for (int i = 0; i <= 10; ++i) {
        ts.push_back(i);
        fs_.push_back(1.0 + v.at("a") * i);
      }
      h.add("t", "1", ts);
      h.add("f", "1", fs_);
      r.tables.push_back(h);
      r.set_scalar("f_end", fs_.back(), "1");
      return r;
    };
    SolverRegistry::instance().add(sv);
  }
  auto check = [](const std::string& key, const std::string& value, const std::string& ref) {
    return "[[checks]]\nkey = \"" + key + "\"\nkind = \"verification\"\nmetric = \"within\"\nvalue = " + value +
           "\nreference = " + ref + "\nunits = \"1\"\nsource = \"exact\"\n";
  };
  const std::string sel = R"({ series = "s", run = "each", table = "hist", output = "f", x = "t", window_fraction = [0.5, 1.0], reduce = "drift")";
  const fs::path f = write_solver_case("toy_drift", "toy_history_solver", R"([[series]]
name = "s"
model = "toy_history_solver"
sweep = { param = "a", values = [0.0, 0.1, -0.1] }
)" + check("one_run", R"({ series = "s", run = 1, table = "hist", output = "f", x = "t", window_fraction = [0.5, 1.0], reduce = "drift" })", "[0.17, 0.18]") +
                                                check("max_abs", sel + R"(, across_runs = "max_abs" })", "[1.1, 1.3]") +
                                                check("max", sel + R"(, across_runs = "max" })", "[0.17, 0.18]") +
                                                check("min", sel + R"(, across_runs = "min" })", "[-1.3, -1.1]") +
                                                check("window_mean", R"({ series = "s", run = 1, table = "hist", output = "f", x = "t", window_fraction = [0.0, 0.5] })", "[1.24, 1.26]"));
  const CaseResult r = run_case(load_case(f, "quick"), "quick", nullptr);
  std::map<std::string, const CheckRecord*> c;
  for (const auto& ch : r.checks) c[ch.key] = &ch;
  // t = 5..10, halves split at 7.5: (1 + 9a) - (1 + 6a) over 1 + 7.5a
  BOOST_TEST(c.at("one_run")->value == 0.3 / 1.75, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(c.at("max_abs")->value == 1.2, boost::test_tools::tolerance(1e-12));  // a = -0.1: -0.3 / 0.25
  BOOST_TEST(c.at("max")->value == 0.3 / 1.75, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(c.at("min")->value == -1.2, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(c.at("window_mean")->value == 1.25, boost::test_tools::tolerance(1e-12));  // t = 0..5
  for (const auto& [k, ch] : c) {
    BOOST_TEST(ch->status == "PASS", k);
    BOOST_TEST(ch->audit.empty(), k + ": " + ch->audit);  // each can fail
  }
  // bad selectors name the field
  for (const std::string& bad : {std::string(R"({ series = "s", run = 0, table = "hist", output = "f", across_runs = "max" })"),
                                 std::string(R"({ series = "s", run = "all", table = "hist", output = "f", x = "t", window = [0, 1] })"),
                                 std::string(R"({ series = "s", run = "each", table = "hist", output = "f", x = "t", window = [0, 10], across_runs = "median" })"),
                                 std::string(R"({ series = "s", run = 0, table = "hist", output = "f", window_fraction = [0.5, 1.0] })"),
                                 std::string(R"({ series = "s", run = 0, table = "hist", output = "f", x = "t", window_fraction = [0.5, 1.5] })"),
                                 std::string(R"({ series = "s", run = 0, table = "hist", output = "f", x = "t", reduce = "drift" })")}) {
    const fs::path g = write_solver_case("toy_drift_bad", "toy_history_solver", R"([[series]]
name = "s"
model = "toy_history_solver"
params = { a = 0.1 }
)" + check("bad", bad, "[0, 1]"));
    BOOST_CHECK_EXCEPTION(load_case(g, "quick"), InputError, [](const InputError& e) {
      return e.field().find(".run") != std::string::npos || e.field().find("across_runs") != std::string::npos ||
             e.field().find("window_fraction") != std::string::npos || e.field().find(".reduce") != std::string::npos;
    });
    fs::remove(g);
  }
  // every run only where a check reduces it to one number: not in a plot line
  {
    const fs::path g = write_solver_case("toy_drift_plot", "toy_history_solver", R"([[series]]
name = "s"
model = "toy_history_solver"
params = { a = 0.1 }
[[plots]]
name = "p"
title = "t"
xlabel = "t"
ylabel = "f"
[[plots.lines]]
series = "s"
run = "each"
table = "hist"
x = "t"
y = "f"
)");
    BOOST_CHECK_EXCEPTION(load_case(g, "quick"), InputError,
                          [](const InputError& e) { return e.field().find(".run") != std::string::npos; });
    fs::remove(g);
  }
  fs::remove(f);
}

// The audit: a comparison of a series with itself cannot fail; a comparison with a number can.
BOOST_AUTO_TEST_CASE(audit_finds_checks_that_cannot_fail) {
  add_toy();
  const fs::path f = write_case("toy_audit", R"(status = "implemented"
[[series]]
name = "line"
model = "toy_linear"
sweep = { param = "x", from = "0 mm", to = "10 mm", n = 11 }
[[checks]]
key = "self_ratio"
kind = "reproduction"
metric = "relative"
value = { ratio = [ { series = "line", output = "y", row = 3 }, { series = "line", output = "y", row = 3 } ] }
reference = 1
tolerance = 0.01
units = "1"
source = "test"
tolerance_source = "test"
[[checks]]
key = "self_reference"
kind = "reproduction"
metric = "relative"
value = { series = "line", output = "y", row = 3 }
reference = { series = "line", output = "y", at = { x = "3 mm" } }
tolerance = 0.01
units = "mm"
source = "test"
tolerance_source = "test"
[[checks]]
key = "argmax_in_sweep"
kind = "reproduction"
metric = "within"
value = { series = "line", output = "y", x = "x", feature = "argmax" }
reference = ["0 mm", "10 mm"]
units = "mm"
source = "test"
tolerance_source = "test"
[[checks]]
key = "echo"
kind = "reproduction"
metric = "absolute"
value = { series = "line", output = "x", row = 2 }
reference = 2
tolerance = 0.1
units = "mm"
source = "test"
tolerance_source = "test"
[[checks]]
key = "honest"
kind = "reproduction"
metric = "relative"
value = { series = "line", output = "y", at = { x = "2 mm" } }
reference = "4 mm"
tolerance = 0.01
units = "mm"
source = "test"
tolerance_source = "test"
[[checks]]
key = "one_minus_min"
kind = "reproduction"
metric = "absolute"
value = { difference = [1, { ratio = [ { series = "line", output = "y", x = "x", window = ["2 mm", "10 mm"], reduce = "min" }, 0.02 ] }] }
reference = 0.3
tolerance = 0.05
units = "1"
source = "test"
tolerance_source = "test"
)");
  const CaseResult r = run_case(load_case(f, "quick"), "quick", nullptr);
  std::map<std::string, std::string> audit;
  for (const auto& c : r.checks) audit[c.key] = c.audit;
  BOOST_TEST(audit["self_ratio"].find("same data") != std::string::npos);
  BOOST_TEST(audit["self_reference"].find("cannot fail") != std::string::npos);
  BOOST_TEST(audit["argmax_in_sweep"].find("cannot fail") != std::string::npos);
  BOOST_TEST(audit["echo"].find("input echo") != std::string::npos);
  BOOST_TEST(audit["honest"].empty());
  // 1 - min y / 0.02 = 0.8 against 0.3 +- 0.05: it passes only for y scaled by 3.25-3.75 or shifted
  // by 0.45-0.55 of its span, between the fixed perturbations; the solve for the scale finds them
  BOOST_TEST(audit["one_minus_min"].empty(), audit["one_minus_min"]);
}

// A recorded check judged again against a changed case file keeps its value and takes the new
// tolerance (paper-resolution records, whose runs take hours).
BOOST_AUTO_TEST_CASE(records_are_rejudged_against_the_case_file) {
  add_toy();
  const fs::path f = write_case("toy_rejudge", R"(status = "implemented"
[[series]]
name = "line"
model = "toy_linear"
params = { x = "1 mm" }
[[checks]]
key = "k"
kind = "reproduction"
metric = "relative"
value = { series = "line", output = "y" }
reference = "2.1 mm"
tolerance = 0.01
units = "mm"
source = "test"
tolerance_source = "test"
)", "[\"quick\", \"full\"]");
  const CaseSpec spec = load_case(f, "full");
  json rec = {{"case", spec.id}, {"status", "PASS"}, {"tier", "full"},
              {"checks", json::array({{{"key", "k"}, {"value", 2.0}, {"reference", 2.1}, {"status", "PASS"}},
                                      {{"key", "gone"}, {"value", 1.0}, {"status", "PASS"}}})}};
  std::vector<std::string> changes;
  const json out = refresh_record(rec, spec, &changes);
  BOOST_TEST(out["checks"].size() == 1u);
  BOOST_TEST(out["checks"][0]["status"].get<std::string>() == "FAIL");  // 2.0 vs 2.1 is 4.8 % > 1 %
  BOOST_TEST(out["checks"][0]["value"].get<double>() == 2.0);
  BOOST_TEST(out["status"].get<std::string>() == "FAIL");
  BOOST_TEST(out["unexpected_failures"].get<int>() == 1);
  BOOST_TEST(changes.size() == 3u);  // k PASS -> FAIL, gone removed, case PASS -> FAIL
}

// The lock of a shared run store: a lock of a process that no longer runs is taken over at once;
// a live holder is waited for.
BOOST_AUTO_TEST_CASE(run_lock_takes_over_dead_holders_and_waits_for_live_ones) {
  const fs::path dir = fs::temp_directory_path() / "cutbench_test_lock";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string run = (dir / "toy-0000000000000001.run").string();
  const std::string lock = (dir / "toy-0000000000000001.lock").string();
  char host[256] = {0};
  ::gethostname(host, sizeof host - 1);
  std::ofstream(lock) << "999999999 " << host << "\n";  // no such process
  BOOST_TEST(!run_in_progress(run));
  {
    const RunLock l(run, nullptr);
    BOOST_TEST(!l.waited());
  }
  BOOST_TEST(!fs::exists(lock));
  std::ofstream(lock) << ::getpid() << " " << host << "\n";  // a live holder (this process)
  BOOST_TEST(run_in_progress(run));  // `cutbench runs --compute` passes over such a run first
  fs::rename(lock, lock + ".held");
  std::ofstream(lock) << ::getpid() << " another-host\n";
  BOOST_TEST(run_in_progress(run));  // a holder on another host cannot be checked: taken as live
  fs::rename(lock + ".held", lock);
  std::thread release([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(2500));
    fs::remove(lock);
  });
  std::string told;
  {
    const RunLock l(run, [&](const std::string& m) { told = m; });
    BOOST_TEST(l.waited());
  }
  release.join();
  BOOST_TEST(told.find("waiting") != std::string::npos);
  fs::remove_all(dir);
}

// The progress log of a run being computed into a store: throttled lines "time fraction", read as
// the last fraction (running) or the last one before a time (a checkpoint's), removed when stored.
BOOST_AUTO_TEST_CASE(progress_log_gives_the_fraction_done) {
  const fs::path dir = fs::temp_directory_path() / "cutbench_test_progress";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string run = (dir / "toy-0000000000000002.run").string();
  BOOST_TEST(run_progress(run, HUGE_VAL) < 0.0);  // nothing recorded
  {
    ProgressLog log(run, 0.0);  // every call writes
    log.note(0.25);
    log.note(0.5);
  }
  BOOST_TEST(run_progress(run, HUGE_VAL) == 0.5);
  BOOST_TEST(run_progress(run, 0.0) < 0.0);  // nothing written before 1970
  ProgressLog throttled(run, 3600.0);
  throttled.note(0.75);  // the first call writes
  throttled.note(0.9);   // within the interval: skipped
  BOOST_TEST(run_progress(run, HUGE_VAL) == 0.75);
  throttled.remove();
  BOOST_TEST(run_progress(run, HUGE_VAL) < 0.0);
  fs::remove_all(dir);
}

// One vocabulary: no model or solver names a shared quantity by a retired name. Beam models keep
// their own symbols for the beam thickness (not the depth of cut): moment_curvature's h and
// dcb_energy_release's d.
BOOST_AUTO_TEST_CASE(shared_quantities_carry_their_glossary_names) {
  const std::set<std::pair<std::string, std::string>> beam = {{"moment_curvature", "h"}, {"dcb_energy_release", "d"}};
  auto check = [&](const std::string& owner, const std::vector<ParamSpec>& params) {
    for (const auto& p : params) {
      if (glossary::retired_names().count(p.name) && !beam.count({owner, p.name})) {
        BOOST_ERROR(owner << " names a shared quantity '" << p.name << "' (glossary: "
                          << glossary::retired_names().at(p.name) << ")");
      }
    }
  };
  for (const auto& m : ModelRegistry::instance().all()) check(m.name, m.params);
  for (const auto& s : SolverRegistry::instance().all()) check(s.name, s.params);
  BOOST_TEST(SolverRegistry::instance().all().size() + ModelRegistry::instance().all().size() > 20u);
}
