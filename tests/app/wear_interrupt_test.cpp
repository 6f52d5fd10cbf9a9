// `railwear wear` under signals, kills and a vanishing database (issue 17), with the built binary
// run as a real child process (fork + exec), real signals and no mocks:
// - SIGTERM / SIGINT during a run: exit 143 / 130, the run shown as "interrupted" by `history`,
//   and `--resume` ends with a database bit-identical to an uninterrupted run's (every stored
//   step: summary, profile, load cases, distributions);
// - a real SIGKILL at each fsync of a whole small run (run creation, every step, the closing
//   checkpoint; tests/tools/kill_at_fsync.cpp, LD_PRELOAD): the database left behind is finished
//   by `--resume` (or, when the kill came before the run existed, by a new run) bit-identically;
// - a run without steps (left by an older railwear killed at its start) is resumable;
// - the database file deleted or replaced under a running study: exit 1 with a message;
// - a sweep line (issue 19) killed with SIGKILL and run again: complete, and its merge holds the
//   same run as an uninterrupted one, nothing lost or doubled;
// - `railwear curving` (the same handler) under SIGTERM and SIGINT in its solve: exit 143 / 130
//   within a contact evaluation, a message naming the entry, its --json not written.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <ios>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "profiles_db/profile_store.h"
#include "tests/app/cli_runner.h"
#include "tests/app/run_fingerprint.h"
#include "tests/app/wear_scenes.h"

namespace railwear::test {
namespace {

// kSmallWearStudy cut to 1e5 passes: 10 steps of about 0.1 s, long enough to be signalled
// after its first steps and short enough to run twice.
std::string ShortStudy() {
  std::string s = kSmallWearStudy;
  s.replace(s.find("total_passes = 4e5"), 18, "total_passes = 1e5");
  return s;
}

// One node per entry and 4e4 passes: 4 steps, 15 fsyncs, about 0.3 s per run.
std::string TinyStudy() {
  std::string s = kSmallWearStudy;
  s.replace(s.find("total_passes = 4e5"), 18, "total_passes = 4e4");
  s.replace(s.find("quadrature_points = 3"), 21, "quadrature_points = 1");
  return s;
}

// TinyStudy with co-evolution (issue 16): the entry's wheel (R8) wears over 3 m per pass (about
// one revolution: the wheel and the rail wear alike, both set steps).
std::string TinyCoEvolutionStudy() {
  std::string s = TinyStudy();
  const std::string elastic = "wheel = { E_MPa = 210000, nu = 0.28 }";
  s.replace(s.find(elastic), elastic.size(), "wheel = { grade = \"R8\" }");
  return s + "wheel_wear = { distance_per_pass_m = 3.0 }\n";
}

constexpr const char* kRun = "small study";

class WearInterruptTest : public CliFixture {
 protected:
  // Starts `railwear ARGS` in dir_ as a child (fork + exec, no shell, so the pid is railwear's
  // own) with `env` added, stdout and stderr to dir_/out.txt and dir_/err.txt.
  pid_t Start(const std::vector<std::string>& args, const std::vector<std::string>& env = {}) {
    std::vector<std::string> argv_text = {RAILWEAR_BINARY};
    argv_text.insert(argv_text.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : argv_text) argv.push_back(a.data());
    argv.push_back(nullptr);
    const std::string out = (dir_ / "out.txt").string(), err = (dir_ / "err.txt").string();
    Write("out.txt", "");  // emptied before the child starts: WaitForStderr reads only its lines
    Write("err.txt", "");
    const pid_t pid = fork();
    if (pid == 0) {
      for (const std::string& e : env) putenv(const_cast<char*>(e.c_str()));
      const int o = open(out.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
      const int e = open(err.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
      if (chdir(dir_.c_str()) != 0 || o < 0 || e < 0) _exit(125);
      dup2(o, 1);
      dup2(e, 2);
      execv(RAILWEAR_BINARY, argv.data());
      _exit(126);
    }
    return pid;
  }

  // The child's exit code, or minus the signal that ended it.
  static int Wait(pid_t pid) {
    int status = 0;
    if (waitpid(pid, &status, 0) != pid) return -1000;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
  }

  // Waits (at most a minute) until the child's stderr holds `text`; false if it ended first.
  bool WaitForStderr(pid_t pid, const std::string& text) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline) {
      if (ReadFile(dir_ / "err.txt").find(text) != std::string::npos) return true;
      siginfo_t info{};  // the child ended (still to be reaped by Wait)?
      if (waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) != 0 ||
          info.si_pid == pid) {
        return ReadFile(dir_ / "err.txt").find(text) != std::string::npos;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return false;
  }

  // The fingerprint of an uninterrupted run of `scene` in dir_/name.
  std::string Reference(const std::string& scene, const std::string& name) {
    const Outcome whole = Run("wear " + scene + " --db " + name + " --threads 1");
    EXPECT_EQ(whole.exit_code, 0) << whole.err;
    return RunFingerprint(dir_ / name);
  }

  // Signals a run once its second step is stored (so the signal lands in a later step's
  // solves or in its commit), then checks the exit code, the stored state and the message,
  // `history`, and that --resume finishes the run bit-identically.
  void InterruptAndResume(int signal, int expected_exit, const char* name) {
    Write("study.toml", ShortStudy());
    const std::string expected = Reference("study.toml", "whole.sqlite");
    const pid_t pid = Start({"wear", "study.toml", "--db", "cut.sqlite", "--threads", "1"});
    ASSERT_TRUE(WaitForStderr(pid, "railwear: step 2:")) << ReadFile(dir_ / "err.txt");
    ASSERT_EQ(kill(pid, signal), 0);
    ASSERT_EQ(Wait(pid), expected_exit) << ReadFile(dir_ / "err.txt");
    const std::string err = ReadFile(dir_ / "err.txt");
    EXPECT_TRUE(Contains(err, std::string("railwear: ") + name +
                                  ": run 'small study' in cut.sqlite interrupted after step "));
    EXPECT_TRUE(Contains(err, "--resume`"));
    {
      const ProfileStore store = ProfileStore::OpenReadOnly((dir_ / "cut.sqlite").string());
      const auto run = store.FindRun(kRun);
      ASSERT_TRUE(run.has_value());
      EXPECT_EQ(run->state, RunState::kInterrupted);
      const int last = *store.LastStep(run->id);
      EXPECT_GE(last, 2);
      EXPECT_TRUE(Contains(err, "interrupted after step " + std::to_string(last) + " "));
    }
    const Outcome runs = Run("history --db cut.sqlite runs");
    ASSERT_EQ(runs.exit_code, 0) << runs.err;
    EXPECT_TRUE(Contains(runs.out, "small study  interrupted"));

    const Outcome resumed = Run("wear study.toml --db cut.sqlite --resume --threads 1");
    ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
    EXPECT_TRUE(Contains(resumed.err, "resuming run 'small study' from step"));
    EXPECT_TRUE(Contains(resumed.err, "passes; it was interrupted)"));
    EXPECT_EQ(RunFingerprint(dir_ / "cut.sqlite"), expected);  // complete, bit for bit
  }

  // Kills a run of `scene` at each of its fsyncs in turn and finishes it (see the tests below).
  void KillAtEachFsync(const std::string& scene) {
    Write("tiny.toml", scene);
    const std::string expected = Reference("tiny.toml", "whole.sqlite");
    const std::string shim = std::string("LD_PRELOAD=") + RAILWEAR_KILL_AT_FSYNC;
    const std::string no_asan_order = "ASAN_OPTIONS=verify_asan_link_order=0";
    const std::vector<std::string> args = {"wear",     "tiny.toml", "--db",
                                           "k.sqlite", "--threads", "1"};
    const pid_t counting = Start(args, {shim, no_asan_order, "RAILWEAR_FSYNC_LOG=fsyncs.txt"});
    ASSERT_EQ(Wait(counting), 0) << ReadFile(dir_ / "err.txt");
    ASSERT_EQ(RunFingerprint(dir_ / "k.sqlite"), expected);  // the shim changes nothing else
    std::istringstream log(ReadFile(dir_ / "fsyncs.txt"));
    int fsyncs = 0;
    for (std::string line; std::getline(log, line);) ++fsyncs;
    ASSERT_GE(fsyncs, 8);  // at least: creation, run + step 0, 4 steps, state, checkpoint

    int resumed = 0, restarted = 0;
    for (int n = 1; n <= fsyncs; ++n) {
      SCOPED_TRACE("killed at fsync " + std::to_string(n) + " of " + std::to_string(fsyncs));
      for (const char* suffix : {"", "-wal", "-shm", "-journal"}) {
        fs::remove(dir_ / ("k.sqlite" + std::string(suffix)));
      }
      const pid_t pid =
          Start(args, {shim, no_asan_order, "RAILWEAR_KILL_AT_FSYNC=" + std::to_string(n)});
      ASSERT_EQ(Wait(pid), -SIGKILL) << ReadFile(dir_ / "err.txt");
      Outcome finish = Run("wear tiny.toml --db k.sqlite --resume --threads 1");
      if (finish.exit_code == 2 && Contains(finish.err, "no run 'small study' to resume")) {
        finish = Run("wear tiny.toml --db k.sqlite --threads 1");  // killed before the run existed
        ++restarted;
      } else {
        ++resumed;
        EXPECT_FALSE(Contains(finish.err, "had no stored step"));  // never a run without step 0
      }
      ASSERT_EQ(finish.exit_code, 0) << finish.err;
      EXPECT_EQ(RunFingerprint(dir_ / "k.sqlite"), expected);
    }
    EXPECT_GE(resumed, 5);    // the kills from the run's creation on
    EXPECT_GE(restarted, 1);  // the kills while the database itself was being created
    std::cerr << "[figure] " << fsyncs << " kill points: " << resumed << " resumed, " << restarted
              << " restarted, all bit-identical\n";
  }
};

TEST_F(WearInterruptTest, SigtermMidRunExits143AndResumesBitIdentically) {
  InterruptAndResume(SIGTERM, 143, "SIGTERM");
}

TEST_F(WearInterruptTest, SigintMidRunExits130AndResumesBitIdentically) {
  InterruptAndResume(SIGINT, 130, "SIGINT");
}

// SIGTERM while a vehicle entry's curving solve runs (issue 17): the solve asks the cancel flag
// between its wheelset contact evaluations (CurvingOptions::cancel), so the run stops within a
// fraction of one solve instead of after it. The signal is sent once the run and its step 0 are
// committed (the 8th fsync, logged by the fsync shim without a kill): railwear then solves the
// vehicle's equilibrium on the unworn rails (RunWear's VehicleStarts) before step 1. Expected:
// exit 143, interrupted after step 0, well within the time of one curving solve (measured here
// with `railwear curving` on the same scene), and --resume bit-identical to an uninterrupted run.
// `railwear curving` (issue 17): the wheelset's solve takes about a second (1.5 s on the
// project's machine); the signal is sent once stderr says the solve started, and the command
// stops within one evaluation of the wheelset's contacts with 128 + signal and a message.
TEST_F(WearInterruptTest, CurvingCommandStopsOnSigtermAndSigintWithItsExitCode) {
  Write("curve.toml", kWheelsetCurveScene);
  // Unsignalled, the command finishes and writes its JSON: the whole solve's time.
  const auto solve_start = std::chrono::steady_clock::now();
  const Outcome whole = Run("curving curve.toml --json eq.json");
  const double solve_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - solve_start).count();
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  ASSERT_TRUE(fs::exists(dir_ / "eq.json"));
  fs::remove(dir_ / "eq.json");
  for (const auto& [signal, code, name] : std::vector<std::tuple<int, int, std::string>>{
           {SIGTERM, 143, "SIGTERM"}, {SIGINT, 130, "SIGINT"}}) {
    const pid_t pid = Start({"curving", "curve.toml", "--json", "eq.json"});
    ASSERT_TRUE(WaitForStderr(pid, "railwear: curving: solving traffic entry"))
        << ReadFile(dir_ / "err.txt");
    const auto signalled = std::chrono::steady_clock::now();
    ASSERT_EQ(kill(pid, signal), 0);
    ASSERT_EQ(Wait(pid), code) << ReadFile(dir_ / "err.txt");
    const double stop_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count();
    const std::string err = ReadFile(dir_ / "err.txt");
    EXPECT_TRUE(Contains(err, "railwear: " + name +
                                  ": curving of curve.toml stopped in the "
                                  "solve of traffic entry '"))
        << err;
    EXPECT_TRUE(Contains(err, "eq.json was not written")) << err;
    EXPECT_FALSE(fs::exists(dir_ / "eq.json"));
    // A solve that ran to its end (and only then saw the signal) would take about the whole
    // solve's time; the cancelled one stops after one evaluation of the wheelset's contacts.
    EXPECT_LT(stop_s, 0.5 * solve_s);
    std::cerr << "[figure] " << name << " in `railwear curving`: stopped in " << stop_s
              << " s; the whole command takes " << solve_s << " s\n";
  }
}

TEST_F(WearInterruptTest, SigtermInTheCurvingSolveStopsItAndResumesBitIdentically) {
  std::string scene = kWheelsetCurveScene;
  scene.replace(scene.find("total_passes = 1e5"), 18, "total_passes = 2e4");
  Write("curve.toml", scene);
  const std::string expected = Reference("curve.toml", "whole.sqlite");
  const auto solve_start = std::chrono::steady_clock::now();
  const Outcome curving = Run("curving curve.toml");
  const double solve_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - solve_start).count();
  ASSERT_EQ(curving.exit_code, 0) << curving.err;

  const std::string shim = std::string("LD_PRELOAD=") + RAILWEAR_KILL_AT_FSYNC;
  const pid_t pid = Start({"wear", "curve.toml", "--db", "cut.sqlite", "--threads", "1"},
                          {shim, "ASAN_OPTIONS=verify_asan_link_order=0",
                           "RAILWEAR_FSYNC_LOG=fsyncs.txt"});
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  int fsyncs = 0;
  while (fsyncs < 8 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::istringstream log(fs::exists(dir_ / "fsyncs.txt") ? ReadFile(dir_ / "fsyncs.txt") : "");
    fsyncs = 0;
    for (std::string line; std::getline(log, line);) ++fsyncs;
  }
  ASSERT_GE(fsyncs, 8) << ReadFile(dir_ / "err.txt");
  const auto signalled = std::chrono::steady_clock::now();
  ASSERT_EQ(kill(pid, SIGTERM), 0);
  ASSERT_EQ(Wait(pid), 143) << ReadFile(dir_ / "err.txt");
  const double stop_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count();
  const std::string err = ReadFile(dir_ / "err.txt");
  EXPECT_TRUE(Contains(err, "run 'wheelset on R1500' in cut.sqlite interrupted after step 0 "))
      << err;
  {
    const ProfileStore store = ProfileStore::OpenReadOnly((dir_ / "cut.sqlite").string());
    const auto run = store.FindRun("wheelset on R1500");
    ASSERT_TRUE(run.has_value());
    EXPECT_EQ(run->state, RunState::kInterrupted);
    EXPECT_EQ(*store.LastStep(run->id), 0);
  }
  // A solve that ran to its end would take the whole solve time; the cancelled one stops after
  // at most one evaluation of the wheelset's contacts (a few of the solve's tens).
  EXPECT_LT(stop_s, 0.5 * solve_s);
  std::cerr << "[figure] SIGTERM in the curving solve: stopped in " << stop_s
            << " s; one curving solve (railwear curving) takes " << solve_s << " s\n";

  const Outcome resumed = Run("wear curve.toml --db cut.sqlite --resume --threads 1");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(RunFingerprint(dir_ / "cut.sqlite"), expected);
}

// A real SIGKILL at the N-th fsync of a whole run, for every N the run makes (counted by a first
// run under the shim): SQLite's journal-mode switch and schema creation, the run with its step 0,
// each step, the final state and the closing checkpoint. After each kill the database must be
// finished bit-identically: by --resume when the run exists (never a run without its step 0),
// by a new run when the kill came before the run was created.
TEST_F(WearInterruptTest, KillAtEachFsyncIsFinishedBitIdentically) {
  KillAtEachFsync(TinyStudy());
}

// The same with co-evolution (issue 16 point 6): the entry's wheel wears and is stored per step
// (wheel_steps), and a killed run resumes with its wheel bit for bit.
TEST_F(WearInterruptTest, KillAtEachFsyncWithAWearingWheelIsFinishedBitIdentically) {
  KillAtEachFsync(TinyCoEvolutionStudy());
}

// A run without steps (left by a railwear before issue 17, killed between the commit that
// created the run and the one of its step 0) is resumable: --resume stores step 0 from the scene
// (whose text is the stored one) and finishes the run as an uninterrupted one.
TEST_F(WearInterruptTest, ARunWithoutStepsIsResumable) {
  Write("tiny.toml", TinyStudy());
  const std::string expected = Reference("tiny.toml", "whole.sqlite");
  {
    const RunInfo whole =
        *ProfileStore::OpenReadOnly((dir_ / "whole.sqlite").string()).FindRun(kRun);
    RunInfo stuck = whole;
    stuck.created_utc.clear();
    stuck.state = RunState::kRunning;
    ProfileStore::Open((dir_ / "stuck.sqlite").string()).CreateRun(stuck);  // no step 0
  }
  const Outcome fresh = Run("wear tiny.toml --db stuck.sqlite");
  EXPECT_EQ(fresh.exit_code, 2);  // the name is taken ...
  EXPECT_TRUE(Contains(fresh.err, "run 'small study' exists already"));
  const Outcome resumed = Run("wear tiny.toml --db stuck.sqlite --resume --threads 1");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;  // ... and resumable
  EXPECT_TRUE(Contains(resumed.err,
                       "run 'small study' had no stored step (its start was "
                       "interrupted): stored its step 0 from the scene"));
  EXPECT_EQ(RunFingerprint(dir_ / "stuck.sqlite"), expected);
}

// The database file deleted (or replaced) under a running study: the next commit notices, the
// study stops with exit 1 and says so, instead of running on into a file nobody can open.
TEST_F(WearInterruptTest, DeletedOrReplacedDatabaseStopsTheRunWithExitOne) {
  Write("study.toml", ShortStudy());
  pid_t pid = Start({"wear", "study.toml", "--db", "gone.sqlite", "--threads", "1"});
  ASSERT_TRUE(WaitForStderr(pid, "railwear: step 1:")) << ReadFile(dir_ / "err.txt");
  fs::remove(dir_ / "gone.sqlite");
  ASSERT_EQ(Wait(pid), 1) << ReadFile(dir_ / "err.txt");
  EXPECT_TRUE(Contains(ReadFile(dir_ / "err.txt"),
                       "railwear: error: database 'gone.sqlite': the file was deleted while "
                       "railwear was writing to it"));

  const std::string other = "a file that is not the study\n";
  Write("other.txt", other);
  pid = Start({"wear", "study.toml", "--db", "swapped.sqlite", "--threads", "1"});
  ASSERT_TRUE(WaitForStderr(pid, "railwear: step 1:")) << ReadFile(dir_ / "err.txt");
  fs::rename(dir_ / "other.txt", dir_ / "swapped.sqlite");
  ASSERT_EQ(Wait(pid), 1) << ReadFile(dir_ / "err.txt");
  EXPECT_TRUE(Contains(ReadFile(dir_ / "err.txt"),
                       "database 'swapped.sqlite': the file was replaced by another file"));
  EXPECT_EQ(ReadFile(dir_ / "swapped.sqlite"), other);  // never written
}

// A Slurm task killed and resubmitted (issue 19): `sweep --index 0` killed with SIGKILL after its
// second step, run again by index, continues the run (the wear --resume path); the line's
// database and the merge of it hold exactly what an uninterrupted run of the line's scene stores.
TEST_F(WearInterruptTest, KilledSweepLineRunAgainMergesWithNothingLostOrDoubled) {
  Write("base.toml", ShortStudy());
  Write("plan.toml",
        "[sweep]\nscene = \"base.toml\"\nout_dir = \"runs\"\n[[axis]]\nkey = \"wear.k\"\n"
        "values = [2.0e-4]\n");
  const Outcome list = Run("sweep plan.toml --list");
  ASSERT_EQ(list.exit_code, 0) << list.err;
  const std::string id = list.out.substr(0, 13);
  const fs::path db = dir_ / "runs" / (id + ".sqlite");

  const pid_t pid = Start({"sweep", "plan.toml", "--index", "0", "--threads", "1"});
  ASSERT_TRUE(WaitForStderr(pid, "railwear: step 2:")) << ReadFile(dir_ / "err.txt");
  ASSERT_EQ(kill(pid, SIGKILL), 0);
  ASSERT_EQ(Wait(pid), -SIGKILL);
  {
    const ProfileStore cut = ProfileStore::OpenReadOnly(db.string());
    EXPECT_EQ(cut.FindRun(id)->state, RunState::kRunning);  // killed: no state written
  }
  const Outcome again = Run("sweep plan.toml --index 0 --threads 1");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_TRUE(Contains(again.err, "sweep line 0 (" + id + "): wear.k=0.0002 (continued)"));
  EXPECT_TRUE(Contains(again.err, "resuming run '" + id + "' from step "));

  // The uninterrupted run of the same scene (the line's scene file) as the reference.
  const Outcome whole =
      Run("wear runs/" + id + ".toml --db whole.sqlite --run " + id + " --threads 1");
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const std::string expected = RunFingerprint(dir_ / "whole.sqlite", id);
  ASSERT_NE(expected, "no run");
  EXPECT_EQ(RunFingerprint(db, id), expected);
  ASSERT_EQ(Run("merge study.sqlite runs/" + id + ".sqlite").exit_code, 0);
  EXPECT_EQ(RunFingerprint(dir_ / "study.sqlite", id), expected);
  ASSERT_EQ(Run("merge study.sqlite runs/" + id + ".sqlite whole.sqlite").exit_code, 0);
  EXPECT_EQ(RunFingerprint(dir_ / "study.sqlite", id), expected);  // the same run: kept once
  const ProfileStore merged = ProfileStore::OpenReadOnly((dir_ / "study.sqlite").string());
  EXPECT_EQ(merged.Runs().size(), 1u);
}

}  // namespace
}  // namespace railwear::test
