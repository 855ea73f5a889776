// Checkpoint writer and reader (layout: include/adrsph/io/checkpoint_h5.hpp).
#include "adrsph/io/checkpoint_h5.hpp"

#include <algorithm>
#include <span>
#include <stdexcept>
#include <string>
#include <system_error>
#include <type_traits>
#include <utility>

#include "io/h5_arrays.hpp"
#include "particles/particle_store.hpp"

namespace adrsph {
namespace {

using h5::read_attribute;
using h5::write_attribute;

h5::Handle create_group(hid_t parent, const char* name, const std::string& file) {
  return h5::check(H5Gcreate2(parent, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, file,
                   std::string("create group ") + name);
}

h5::Handle open_group(hid_t parent, const char* name, const std::string& file) {
  return h5::check(H5Gopen2(parent, name, H5P_DEFAULT), H5Gclose, file,
                   std::string("open group /") + name);
}

// Every array of a checkpoint is checksummed (Fletcher-32); its metadata (groups,
// attributes) too, by the file format of write_checkpoint (object header checksums).
template <class T>
void put(hid_t g, const char* name, const std::vector<T>& v, const std::string& file) {
  h5::write_dataset<T>(g, name, std::span<const T>(v), file, /*checksum=*/true);
}

template <class T>
std::vector<T> get(hid_t g, const char* group, const char* name, const std::string& file) {
  return h5::read_dataset<T>(g, std::string("/") + group, name, file);
}

void put_text(hid_t g, const char* name, const std::string& text, const std::string& file) {
  put(g, name, std::vector<std::uint8_t>(text.begin(), text.end()), file);
}

std::string get_text(hid_t g, const char* group, const char* name, const std::string& file) {
  const auto bytes = get<std::uint8_t>(g, group, name, file);
  return {bytes.begin(), bytes.end()};
}

void put_long(hid_t g, const char* name, long v, const std::string& file) {
  write_attribute<std::int64_t>(g, name, v, file);
}

long get_long(hid_t g, const char* name, const std::string& file) {
  return static_cast<long>(read_attribute<std::int64_t>(g, name, file));
}

// Rows of equal length, flattened; the row length is stored beside them.
void put_rows(hid_t g, const char* name, const std::vector<std::vector<double>>& rows,
              const std::string& file) {
  std::vector<double> flat;
  const std::size_t width = rows.empty() ? 0 : rows.front().size();
  for (const auto& r : rows) {
    if (r.size() != width) throw std::runtime_error(file + ": rows of " + name + " differ");
    flat.insert(flat.end(), r.begin(), r.end());
  }
  put(g, name, flat, file);
  put_long(g, (std::string(name) + "_width").c_str(), static_cast<long>(width), file);
}

std::vector<std::vector<double>> get_rows(hid_t g, const char* group, const char* name,
                                          const std::string& file) {
  const auto flat = get<double>(g, group, name, file);
  const long width = get_long(g, (std::string(name) + "_width").c_str(), file);
  std::vector<std::vector<double>> rows;
  if (width <= 0) return rows;
  if (flat.size() % static_cast<std::size_t>(width) != 0)
    throw std::runtime_error(file + ": /" + group + "/" + name + " is not whole rows");
  for (std::size_t i = 0; i < flat.size(); i += width)
    rows.emplace_back(flat.begin() + i, flat.begin() + i + width);
  return rows;
}

std::vector<double> flatten(const ProbeTable& p) {
  std::vector<double> v;
  for (const auto* a : {&p.x_mm, &p.c_y0, &p.c_yp25, &p.c_ym25, &p.c_mean})
    v.insert(v.end(), a->begin(), a->end());
  return v;
}

ProbeTable unflatten(const std::vector<double>& v, const std::string& file) {
  if (v.size() % 5 != 0) throw std::runtime_error(file + ": malformed probe table");
  const std::size_t n = v.size() / 5;
  ProbeTable p;
  std::vector<double>* cols[] = {&p.x_mm, &p.c_y0, &p.c_yp25, &p.c_ym25, &p.c_mean};
  for (std::size_t k = 0; k < 5; ++k) cols[k]->assign(v.begin() + k * n, v.begin() + (k + 1) * n);
  return p;
}

// The solver snapshot's fields, listed once for the writer and the reader.
template <class T>
using Array = std::vector<T> SolverSnapshot::*;
constexpr std::pair<const char*, Array<double>> kSolverDoubles[] = {
    {"inflow_row_tail", &SolverSnapshot::inflow_row_tail},
    {"phase_seconds", &SolverSnapshot::phase_seconds}};
constexpr std::pair<const char*, double SolverSnapshot::*> kSolverScalars[] = {
    {"t", &SolverSnapshot::t}, {"particle_steps", &SolverSnapshot::particle_steps}};
constexpr std::pair<const char*, long SolverSnapshot::*> kSolverCounters[] = {
    {"steps", &SolverSnapshot::steps},
    {"lost", &SolverSnapshot::lost},
    {"lost_reported", &SolverSnapshot::lost_reported},
    {"rebuilds", &SolverSnapshot::rebuilds},
    {"entered", &SolverSnapshot::entered},
    {"left", &SolverSnapshot::left}};
// Counters kept since checkpoints were first written: a checkpoint without one reads 0.
constexpr std::pair<const char*, long SolverSnapshot::*> kSolverLaterCounters[] = {
    {"two_pass_builds", &SolverSnapshot::two_pass_builds}};

void write_solver(hid_t root, const SolverSnapshot& s, const std::string& file) {
  const auto g = create_group(root, "solver", file);
  const hid_t id = g.get();
  // The particle arrays under their store names (/solver/x, /solver/kind, ...).
  auto put_arrays = [&](const auto& arrays) {
    for (const auto& a : arrays) h5::write_dataset(id, a.name, a.values(), file, true);
  };
  put_arrays(s.particles.f64);
  put_arrays(s.particles.f32);
  put_arrays(s.particles.u8);
  for (const auto& [name, field] : kSolverDoubles) put(id, name, s.*field, file);
  for (const auto& [name, field] : kSolverScalars) write_attribute(id, name, s.*field, file);
  for (const auto& [name, field] : kSolverCounters) put_long(id, name, s.*field, file);
  for (const auto& [name, field] : kSolverLaterCounters) put_long(id, name, s.*field, file);
  put(id, "ledger", std::vector<double>(s.ledger.begin(), s.ledger.end()), file);
}

SolverSnapshot read_solver(hid_t root, const std::string& file) {
  const auto g = open_group(root, "solver", file);
  const hid_t id = g.get();
  const char* grp = "solver";
  SolverSnapshot s;
  // The particle arrays the store's field list names as state (checkpoint.hpp).
  // Its list with every optional array: those a run does not have are not in the file (a
  // case of one species writes no c_1, a modern-scheme run no predicted_density).
  ParticleStore layout;  // empty: only its field list is read
  ParticleStore::Needs all;
  all.more_species = ParticleStore::kMaxMore;
  all.predicted_density = true;
  layout.set_needs(all);
  ParticleStore empty;
  ParticleStore::for_each_field(layout, [&](auto& a, ParticleStore::Role role, const char* name) {
    if (role != ParticleStore::Role::state) return;
    bool in_default = false;  // the arrays of every run must be there; the others may be
    ParticleStore::for_each_field(empty, [&](auto&, ParticleStore::Role, const char* other) {
      in_default = in_default || std::string(other) == name;
    });
    if (!in_default && H5Lexists(id, name, H5P_DEFAULT) <= 0) return;
    using T = typename std::decay_t<decltype(a)>::value_type;
    s.particles.of<T>().emplace_back(name, get<T>(id, grp, name, file));
  });
  for (const auto& [name, field] : kSolverDoubles) s.*field = get<double>(id, grp, name, file);
  for (const auto& [name, field] : kSolverScalars)
    s.*field = read_attribute<double>(id, name, file);
  for (const auto& [name, field] : kSolverCounters) s.*field = get_long(id, name, file);
  for (const auto& [name, field] : kSolverLaterCounters)
    if (H5Lexists(id, name, H5P_DEFAULT) > 0) s.*field = get_long(id, name, file);
  const auto ledger = get<double>(id, grp, "ledger", file);
  if (ledger.size() != s.ledger.size() && ledger.size() != 4)  // 4: the first species only
    throw std::runtime_error(file + ": malformed /solver/ledger");
  std::copy(ledger.begin(), ledger.end(), s.ledger.begin());
  return s;
}

void write_run(hid_t root, const RunCheckpoint& r, const std::string& file) {
  const auto g = create_group(root, "run", file);
  const hid_t id = g.get();
  put(id, "steady_t", r.steady.t, file);
  put_rows(id, "steady_values", r.steady.values, file);
  put_long(id, "steady", r.steady.steady ? 1 : 0, file);
  write_attribute(id, "t_steady", r.steady.t_steady, file);
  std::vector<double> window_t, history_t, history_change;
  std::vector<std::vector<double>> window_tables, history_stations;
  for (const auto& [t, p] : r.average_window) {
    window_t.push_back(t);
    window_tables.push_back(flatten(p));
  }
  for (const HistoryRow& h : r.history) {
    history_t.push_back(h.t);
    history_stations.push_back(h.stations);
    history_change.push_back(h.steady_change);
  }
  put(id, "window_t", window_t, file);
  put_rows(id, "window_tables", window_tables, file);
  put(id, "history_t", history_t, file);
  put_rows(id, "history_stations", history_stations, file);
  put(id, "history_change", history_change, file);
  std::vector<std::vector<double>> outlet;
  for (const OutletRow& o : r.outlet) outlet.push_back({o.t, o.c_flow, o.c_section});
  put_rows(id, "outlet", outlet, file);
  put_text(id, "jitter_state", r.jitter_state, file);
  write_attribute(id, "next_check", r.next_check, file);
  put_long(id, "next_field", static_cast<long>(r.next_field), file);
  write_attribute(id, "wall_s", r.wall_s, file);
  write_attribute(id, "stepping_wall_s", r.stepping_wall_s, file);
  write_attribute(id, "peak_rss_bytes", r.peak_rss_bytes, file);
  put_long(id, "restarts", r.restarts, file);
  put_long(id, "warm_started", r.warm_started ? 1 : 0, file);
  put_long(id, "warm_start_steady", r.warm_start_steady ? 1 : 0, file);
  write_attribute(id, "warm_start_t", r.warm_start_t, file);
  write_attribute(id, "warm_start_wall_s", r.warm_start_wall_s, file);
  put_long(id, "warm_start_steps", r.warm_start_steps, file);
}

void read_run(hid_t root, RunCheckpoint& r, const std::string& file) {
  const auto g = open_group(root, "run", file);
  const hid_t id = g.get();
  const char* grp = "run";
  r.steady.t = get<double>(id, grp, "steady_t", file);
  r.steady.values = get_rows(id, grp, "steady_values", file);
  if (r.steady.values.size() != r.steady.t.size())
    throw std::runtime_error(file + ": /run/steady_values does not match /run/steady_t");
  r.steady.steady = get_long(id, "steady", file) != 0;
  r.steady.t_steady = read_attribute<double>(id, "t_steady", file);
  const auto window_t = get<double>(id, grp, "window_t", file);
  const auto window_tables = get_rows(id, grp, "window_tables", file);
  if (window_tables.size() != window_t.size())
    throw std::runtime_error(file + ": /run/window_tables does not match /run/window_t");
  for (std::size_t i = 0; i < window_t.size(); ++i)
    r.average_window.emplace_back(window_t[i], unflatten(window_tables[i], file));
  const auto history_t = get<double>(id, grp, "history_t", file);
  const auto history_stations = get_rows(id, grp, "history_stations", file);
  const auto history_change = get<double>(id, grp, "history_change", file);
  if (history_stations.size() != history_t.size() || history_change.size() != history_t.size())
    throw std::runtime_error(file + ": /run/history arrays differ in length");
  for (std::size_t i = 0; i < history_t.size(); ++i)
    r.history.push_back({history_t[i], history_stations[i], history_change[i]});
  // (absent from checkpoints written before outlet.csv existed: no samples then)
  if (H5Lexists(id, "outlet", H5P_DEFAULT) > 0) {
    for (const auto& row : get_rows(id, grp, "outlet", file)) {
      if (row.size() != 3) throw std::runtime_error(file + ": /run/outlet rows need 3 values");
      r.outlet.push_back({row[0], row[1], row[2]});
    }
  }
  r.jitter_state = get_text(id, grp, "jitter_state", file);
  r.next_check = read_attribute<double>(id, "next_check", file);
  r.next_field = static_cast<std::size_t>(get_long(id, "next_field", file));
  r.wall_s = read_attribute<double>(id, "wall_s", file);
  r.stepping_wall_s = read_attribute<double>(id, "stepping_wall_s", file);
  r.peak_rss_bytes = read_attribute<double>(id, "peak_rss_bytes", file);
  r.restarts = static_cast<int>(get_long(id, "restarts", file));
  r.warm_started = get_long(id, "warm_started", file) != 0;
  r.warm_start_steady = get_long(id, "warm_start_steady", file) != 0;
  r.warm_start_t = read_attribute<double>(id, "warm_start_t", file);
  r.warm_start_wall_s = read_attribute<double>(id, "warm_start_wall_s", file);
  r.warm_start_steps = get_long(id, "warm_start_steps", file);
}

}  // namespace

void write_checkpoint(const std::filesystem::path& path, const CheckpointFile& cp) {
  write_checkpoint(path, cp, cp.state);
}

void write_checkpoint(const std::filesystem::path& path, const CheckpointFile& cp,
                      const RunCheckpoint& state) {
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  const std::string file = tmp.string();
  h5::silence_errors();
  {
    // The 1.10 file format (superblock v3, object header v2) checksums all metadata, so a
    // damaged attribute or group is found on reading too, not only a damaged array.
    const auto access = h5::check(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, file, "file properties");
    h5::check(H5Pset_libver_bounds(access.get(), H5F_LIBVER_V110, H5F_LIBVER_LATEST), file,
              "file format");
    const auto f = h5::check(H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get()),
                             H5Fclose, file, "create the file");
    {
      const auto g = create_group(f.get(), "case", file);
      put_text(g.get(), "case_text", cp.case_text, file);
      put_text(g.get(), "case_file", cp.case_file, file);
      std::string lines;
      for (const auto& o : cp.overrides) lines += o + "\n";
      put_text(g.get(), "overrides", lines, file);
      put_long(g.get(), "threads", cp.threads, file);
    }
    write_solver(f.get(), state.solver, file);
    write_run(f.get(), state, file);
    h5::check(H5Fflush(f.get(), H5F_SCOPE_GLOBAL), file, "flush");
  }
  h5::release_write_buffers();  // as after a field frame (fields_h5.cpp)
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec)
    throw std::runtime_error(path.string() + ": cannot replace the checkpoint: " + ec.message());
}

namespace {

CheckpointFile read_checkpoint_file(const std::string& file) {
  h5::silence_errors();
  const auto f = h5::check(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, file,
                           "open the checkpoint");
  CheckpointFile cp;
  {
    const auto g = open_group(f.get(), "case", file);
    cp.case_text = get_text(g.get(), "case", "case_text", file);
    cp.case_file = get_text(g.get(), "case", "case_file", file);
    const std::string lines = get_text(g.get(), "case", "overrides", file);
    std::size_t start = 0;
    for (std::size_t nl; (nl = lines.find('\n', start)) != std::string::npos; start = nl + 1)
      cp.overrides.push_back(lines.substr(start, nl - start));
    cp.threads = static_cast<int>(get_long(g.get(), "threads", file));
  }
  cp.state.solver = read_solver(f.get(), file);
  read_run(f.get(), cp.state, file);
  return cp;
}

}  // namespace

CheckpointFile read_checkpoint(const std::filesystem::path& path) {
  const std::string file = path.string();
  try {
    return read_checkpoint_file(file);
  } catch (const std::exception& e) {
    // A checksum mismatch, a truncated file or a missing part: never load it.
    throw std::runtime_error(std::string(e.what()) +
                             ": the checkpoint is damaged or incomplete and was not loaded; "
                             "start the run again without --restart");
  }
}

}  // namespace adrsph
