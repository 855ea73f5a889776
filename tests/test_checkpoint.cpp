// Checkpoint/restart: a run stopped at a checkpoint and continued ends exactly (bit for bit,
// one thread) where the uninterrupted run ends; periodic checkpoints change nothing; the CLI
// stops on SIGTERM with a checkpoint and `run --restart` finishes the run.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <omp.h>

#include <nlohmann/json.hpp>
#include <optional>

#include "adrsph/io/checkpoint_h5.hpp"
#include "adrsph/io/output_dir.hpp"
#include "adrsph/simulation.hpp"
#include "io_test_util.hpp"
#include "sph_test_cases.hpp"

namespace adrsph {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

struct FinalState {
  std::vector<double> x, y, vx, vy, rho, c;
  long step = 0;
};

// Keeps the last frame; asks for a checkpoint after `at` steps (once), or every `every` steps.
class Recorder : public RunObserver {
 public:
  Recorder(long at, long every, CheckpointRequest kind) : at_(at), every_(every), kind_(kind) {}
  void on_fields(const FieldFrame& f) override {
    last = FinalState{{f.x.begin(), f.x.end()},
                      {f.y.begin(), f.y.end()},
                      {f.vx.begin(), f.vx.end()},
                      {f.vy.begin(), f.vy.end()},
                      {f.rho.begin(), f.rho.end()},
                      {f.c.begin(), f.c.end()},
                      f.step};
  }
  CheckpointRequest checkpoint_request(double) override {
    ++calls_;
    if (every_ > 0 && calls_ % every_ == 0) return kind_;
    if (at_ > 0 && calls_ == at_) return kind_;
    return CheckpointRequest::none;
  }
  void on_checkpoint(const RunCheckpoint& cp) override {
    checkpoint = cp;
    ++checkpoints;
  }
  FinalState last;
  std::optional<RunCheckpoint> checkpoint;
  int checkpoints = 0;

 private:
  long at_, every_, calls_ = 0;
  CheckpointRequest kind_;
};

Case short_run(Scheme scheme, Flow flow) {
  Case c = testing::short_channel(scheme, flow);
  c.time.max_steps = 240;
  c.time.check_interval = 0.002;  // several probe checks (jitter, history) on either side
  c.time.stop_when_steady = false;
  c.output.field_times = {};
  // A pulse at the inlet and the outlet series: both continue exactly too.
  c.species.feed.shape = FeedShape::pulse;
  c.species.feed.t0 = 0.005;
  c.species.feed.width = 0.005;
  c.species.feed.base = 0.5;
  c.output.outlet_interval = 0.001;
  return c;
}

void expect_same(const FinalState& a, const FinalState& b) {
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.vx, b.vx);
  EXPECT_EQ(a.vy, b.vy);
  EXPECT_EQ(a.rho, b.rho);
  EXPECT_EQ(a.c, b.c);
}

class RestartIsExact : public ::testing::TestWithParam<std::pair<Scheme, Flow>> {};

TEST_P(RestartIsExact, StoppedAndContinuedEqualsUninterrupted) {
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const Case c = short_run(GetParam().first, GetParam().second);

  Recorder whole(0, 0, CheckpointRequest::none);
  const RunResult a = run_simulation(c, whole);
  ASSERT_EQ(a.status, "ok") << a.message;

  Recorder first(100, 0, CheckpointRequest::write_and_stop);
  const RunResult b1 = run_simulation(c, first);
  ASSERT_EQ(b1.status, "interrupted");
  ASSERT_TRUE(first.checkpoint.has_value());
  EXPECT_GE(b1.steps, 100);
  EXPECT_LT(b1.steps, 240);

  // Through the file, as `run --restart` reads it.
  test::TempDir dir;
  CheckpointFile file;
  file.state = *first.checkpoint;
  file.case_text = "name = \"x\"\n";
  file.overrides = {"a=1", "b=2"};
  file.threads = 1;
  write_checkpoint(dir / "cp.h5", file);
  const CheckpointFile read = read_checkpoint(dir / "cp.h5");
  EXPECT_EQ(read.overrides, file.overrides);
  EXPECT_EQ(read.case_text, file.case_text);

  Recorder second(0, 0, CheckpointRequest::none);
  const RunResult b2 = run_simulation(c, second, &read.state);
  ASSERT_EQ(b2.status, "ok") << b2.message;
  expect_same(whole.last, second.last);
  EXPECT_EQ(a.steps, b2.steps);
  EXPECT_EQ(a.stations.c_mean, b2.stations.c_mean);
  EXPECT_EQ(a.history.size(), b2.history.size());
  ASSERT_EQ(a.outlet.size(), b2.outlet.size());
  EXPECT_GT(a.outlet.size(), 10u);
  for (std::size_t i = 0; i < a.outlet.size(); ++i) {
    EXPECT_EQ(a.outlet[i].t, b2.outlet[i].t) << i;
    EXPECT_EQ(a.outlet[i].c_flow, b2.outlet[i].c_flow) << i;
    EXPECT_EQ(a.outlet[i].c_section, b2.outlet[i].c_section) << i;
  }
  EXPECT_EQ(a.list_rebuilds, b2.list_rebuilds);
  EXPECT_EQ(b2.restarts, 1);
  omp_set_num_threads(threads);
}

INSTANTIATE_TEST_SUITE_P(Schemes, RestartIsExact,
                         ::testing::Values(std::pair{Scheme::modern, Flow::wcsph},
                                           std::pair{Scheme::conventional, Flow::wcsph},
                                           std::pair{Scheme::modern, Flow::prescribed}),
                         [](const auto& info) {
                           return std::string(to_string(info.param.first)) + "_" +
                                  to_string(info.param.second);
                         });

// A snapshot's array views the store (no copy on the way to the file); a copy owns its values,
// so it keeps them when the store moves on; a moved owning array keeps its values.
TEST(Checkpoint, NamedArrayViewsAndCopiesOwn) {
  std::vector<double> store{1.0, 2.0, 3.0};
  const NamedArray<double> view("x", std::span<const double>(store));
  EXPECT_EQ(view.values().data(), store.data());
  NamedArray<double> copy = view;
  EXPECT_NE(copy.values().data(), store.data());
  store[1] = 20.0;
  EXPECT_EQ(view.values()[1], 20.0);
  EXPECT_EQ(copy.values()[1], 2.0);
  NamedArray<double> assigned("y", std::vector<double>{});
  assigned = view;
  EXPECT_EQ(assigned.name, "x");
  ASSERT_EQ(assigned.values().size(), 3u);
  EXPECT_EQ(assigned.values()[1], 20.0);
  const NamedArray<double> moved = std::move(copy);
  ASSERT_EQ(moved.values().size(), 3u);
  EXPECT_EQ(moved.values()[0], 1.0);
  EXPECT_EQ(moved.values()[1], 2.0);
}

TEST(Checkpoint, PeriodicCheckpointsChangeNothing) {
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const Case c = short_run(Scheme::modern, Flow::wcsph);
  Recorder plain(0, 0, CheckpointRequest::none);
  run_simulation(c, plain);
  Recorder periodic(0, 30, CheckpointRequest::write);
  const RunResult r = run_simulation(c, periodic);
  EXPECT_EQ(r.status, "ok");
  EXPECT_GE(periodic.checkpoints, 4);
  expect_same(plain.last, periodic.last);
  omp_set_num_threads(threads);
}

// Watching a run does not change it: probe checks every 0.002 s or every 0.05 s (and with
// them the steady test's samples) leave the same trajectory and the same list rebuilds.
TEST(Checkpoint, ProbeChecksChangeNothing) {
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  for (const Flow flow : {Flow::wcsph, Flow::prescribed}) {
    Case often = short_run(Scheme::modern, flow), rarely = often;
    rarely.time.check_interval = 0.05;
    Recorder a(0, 0, CheckpointRequest::none), b(0, 0, CheckpointRequest::none);
    const RunResult ra = run_simulation(often, a);
    const RunResult rb = run_simulation(rarely, b);
    ASSERT_EQ(ra.status, "ok") << ra.message;
    ASSERT_EQ(rb.status, "ok") << rb.message;
    EXPECT_EQ(ra.list_rebuilds, rb.list_rebuilds);
    expect_same(a.last, b.last);
  }
  omp_set_num_threads(threads);
}

TEST(Checkpoint, UnreadableFileNamesIt) {
  test::TempDir dir;
  test::write_file(dir / "bad.h5", "not hdf5");
  try {
    read_checkpoint(dir / "bad.h5");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.h5"));
  }
}

std::string lfr() {
  std::string s(1, '\'');
  s += (test::source_dir() / "cases" / "lfr.toml").string();
  s += '\'';
  return s;
}

// SIGTERM: exit 4 with a checkpoint; a fresh run into the same DIR is refused; a restart may
// not change the physics; `run --restart` finishes with the outputs and no staging left.
TEST(CliCheckpoint, SigtermThenRestart) {
  test::TempDir dir;
  const std::string run = std::string(ADRSPH_BINARY) + " run " + lfr() +
                          " --set particles.dx=0.5 --set time.t_end=5 --set "
                          "time.stop_when_steady=false --set 'output.field_times=[0.0001]' "
                          "--out out --threads 1 --quiet";
  const std::string script = run +
                             " & pid=$!; for i in $(seq 200); do [ -f out.partial/case.toml ] && "
                             "break; sleep 0.05; done; sleep 1; kill -TERM $pid; wait $pid; "
                             "echo exit=$?";
  const auto r = test::run_shell(script, dir.path());
  EXPECT_THAT(r.out, HasSubstr("exit=4")) << r.err;
  EXPECT_THAT(r.err, HasSubstr("adrsph run --restart out"));
  const fs::path cp = StagedDir::checkpoint_path(dir / "out");
  ASSERT_TRUE(fs::exists(cp));
  const long steps = read_checkpoint(cp).state.solver.steps;
  EXPECT_GT(steps, 0);

  const auto again = test::run_adrsph(
      "run " + lfr() + " --set particles.dx=0.5 --out out --threads 1 --quiet", dir.path());
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_THAT(again.err, HasSubstr("--restart"));
  EXPECT_TRUE(fs::exists(cp));

  const auto physics = test::run_adrsph("run --restart out --set species.D=1", dir.path());
  EXPECT_EQ(physics.exit_code, 2);
  EXPECT_THAT(physics.err, HasSubstr("species.D"));

  const auto cont = test::run_adrsph(
      "run --restart out --quiet --set time.max_steps=" + std::to_string(steps + 30), dir.path());
  ASSERT_EQ(cont.exit_code, 0) << cont.err;
  EXPECT_FALSE(fs::exists(dir / "out.partial"));
  EXPECT_FALSE(fs::exists(dir / "out" / "checkpoint.h5"));
  const auto j = nlohmann::json::parse(test::read_file(dir / "out" / "run.json"));
  EXPECT_EQ(j["restarts"].get<int>(), 1);
  EXPECT_EQ(j["steps"].get<long>(), steps + 30);
  // t = 1e-4 (step 2: written before the signal, kept in the appended fields.h5) and the end
  EXPECT_EQ(j["field_frames"].get<int>(), 2);
}

// A run killed without warning (SIGKILL) at a random moment, possibly while it writes a
// checkpoint, continues from its last complete checkpoint: checkpoints are written to a
// .tmp file and renamed into place, so the one on disk is always whole.
TEST(CliCheckpoint, SigkilledRunRestartsFromItsLastCheckpoint) {
  for (const char* delay : {"0", "0.13", "0.29"}) {
    SCOPED_TRACE(std::string("killed ") + delay + " s after its first checkpoint");
    test::TempDir dir;
    const std::string run = std::string(ADRSPH_BINARY) + " run " + lfr() +
                            " --set particles.dx=0.5 --set time.t_end=5 --set "
                            "time.stop_when_steady=false --set output.field_times=[] --set "
                            "output.checkpoint_minutes=0.001 --out out --threads 1 --quiet";
    const std::string script =
        run +
        " & pid=$!; for i in $(seq 3000); do [ -f out.partial/checkpoint.h5 ] && break; "
        "sleep 0.02; done; sleep " +
        delay + "; kill -KILL $pid; wait $pid; echo exit=$?";
    const auto r = test::run_shell(script, dir.path());
    EXPECT_THAT(r.out, HasSubstr("exit=137")) << r.err;
    const fs::path cp = StagedDir::checkpoint_path(dir / "out");
    ASSERT_TRUE(fs::exists(cp));
    const long steps = read_checkpoint(cp).state.solver.steps;
    const auto cont = test::run_adrsph(
        "run --restart out --quiet --set time.max_steps=" + std::to_string(steps + 20), dir.path());
    ASSERT_EQ(cont.exit_code, 0) << cont.err;
    EXPECT_FALSE(fs::exists(dir / "out.partial"));
    EXPECT_FALSE(fs::exists(dir / "out" / "checkpoint.h5.tmp"));
    const auto j = nlohmann::json::parse(test::read_file(dir / "out" / "run.json"));
    EXPECT_EQ(j["status"], "ok");
    EXPECT_EQ(j["steps"].get<long>(), steps + 20);
  }
}

// A damaged checkpoint (cut short, or bytes changed inside: HDF5's checksums on every array
// and on the metadata) is refused with a message naming it, and left as it was.
TEST(CliCheckpoint, DamagedCheckpointIsRefused) {
  test::TempDir dir;
  const std::string run = std::string(ADRSPH_BINARY) + " run " + lfr() +
                          " --set particles.dx=0.5 --set time.t_end=5 --set "
                          "time.stop_when_steady=false --set output.field_times=[] --out out "
                          "--threads 1 --quiet";
  const auto r = test::run_shell(run +
                                     " & pid=$!; for i in $(seq 200); do [ -f "
                                     "out.partial/case.toml ] && break; sleep 0.05; done; "
                                     "sleep 0.5; kill -TERM $pid; wait $pid; echo exit=$?",
                                 dir.path());
  ASSERT_THAT(r.out, HasSubstr("exit=4")) << r.err;
  const fs::path cp = StagedDir::checkpoint_path(dir / "out");
  const std::string whole = test::read_file(cp);
  ASSERT_GT(whole.size(), 10000u);
  struct Damage {
    const char* what;
    std::string bytes;
  };
  std::string flipped = whole;
  for (std::size_t i = whole.size() / 2; i < whole.size() / 2 + 64; ++i)
    flipped[i] = static_cast<char>(~flipped[i]);
  for (const Damage& d : {Damage{"cut in half", whole.substr(0, whole.size() / 2)},
                          Damage{"64 bytes inverted in the middle", flipped}}) {
    SCOPED_TRACE(d.what);
    test::write_file(cp, d.bytes);
    const auto again = test::run_adrsph("run --restart out --quiet", dir.path());
    EXPECT_NE(again.exit_code, 0);
    EXPECT_THAT(again.err, HasSubstr("checkpoint.h5"));
    EXPECT_THAT(again.err, HasSubstr("damaged or incomplete"));
    EXPECT_TRUE(test::read_file(cp) == d.bytes);  // left as it was, for the user to look at
    EXPECT_FALSE(fs::exists(dir / "out"));
  }
  test::write_file(cp, whole);  // the undamaged file still continues
  const auto cont = test::run_adrsph("run --restart out --quiet --set time.max_steps=" +
                                         std::to_string(read_checkpoint(cp).state.solver.steps + 5),
                                     dir.path());
  EXPECT_EQ(cont.exit_code, 0) << cont.err;
}

}  // namespace
}  // namespace adrsph
