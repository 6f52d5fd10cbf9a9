// `railwear sweep` past one machine on real engines (issue 19): the same plan gives the same
// study database, bit for bit (every stored value of every run: RunFingerprint), when run
// - serially (`sweep` then `sweep --merge`), the reference;
// - under `mpirun -n 2 --oversubscribe ... --mpi` (Open MPI; both ranks run lines, largest
//   expected cost first, rank 0 merges);
// - as the generated Slurm job array's lines, run with SLURM_ARRAY_TASK_ID set, then its merge
//   job's line (everywhere);
// - as a real job array and dependent merge job on a single-node Slurm (munged, slurmctld and
//   slurmd on localhost, started and stopped here; skipped, with the daemons' error, where
//   Slurm cannot start).
// Also: a rank killed with SIGKILL, then the sweep run again (nothing lost or doubled); the
// scripts' resources, array range and index line; the merge job refusing incomplete lines.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <regex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "profiles_db/profile_store.h"
#include "tests/app/cli_runner.h"
#include "tests/app/run_fingerprint.h"
#include "tests/app/single_node_slurm.h"
#include "tests/app/sweep_test_support.h"

namespace railwear::test {
namespace {

// Four lines: two wear coefficients x one or two spread nodes. The two-node lines cost twice
// as much (SweepLineCost): lines 1 and 3 go first.
const char* const kPlan = R"([sweep]
scene = "base.toml"
out_dir = "runs"

[[axis]]
key = "wear.k"
values = [1.0e-4, 2.0e-4]

[[axis]]
key = "wear.quadrature_points"
values = [1, 2]
)";

// Open MPI refuses root unless told (CI runs as root).
constexpr const char* kMpiEnv = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1";

class SweepClusterTest : public CliFixture {
 protected:
  void SetUp() override {
    CliFixture::SetUp();
    // The small study cut to 3e4 passes: 3 to 5 steps, well under a second a run.
    Write("base.toml", SmallStudyOfPasses("3e4"));
    Write("plan.toml", kPlan);
  }
  // The manifest's run ids, in order.
  std::vector<std::string> Ids() const {
    const Outcome o = Run("sweep plan.toml --list");
    EXPECT_EQ(o.exit_code, 0) << o.err;
    return ManifestIds(o.out);
  }
  // Every run of the study database `db` (relative to dir_), bit for bit, in manifest order,
  // and how many runs it holds.
  std::string StudyFingerprint(const std::string& db) const {
    std::string out;
    for (const std::string& id : Ids()) out += id + "\n" + RunFingerprint(dir_ / db, id);
    const ProfileStore store = ProfileStore::OpenReadOnly((dir_ / db).string());
    return out + "runs: " + std::to_string(store.Runs().size()) + "\n";
  }
  // Starts `slurm`; "" when it is up, else the reason to skip the test.
  static std::string StartOrWhyNot(SingleNodeSlurm* slurm) {
    const std::string why_not = slurm->Start();
    if (why_not.empty()) return "";
    return "a single-node Slurm (munged, slurmctld, slurmd on localhost) cannot start here, so "
           "the job array is tested by its script's lines alone "
           "(SlurmArrayScriptLinesRunWithTaskId...): " +
           why_not;
  }
  // Runs `DIR/submit.sh ARGS` on `slurm`; the ids of the job array and of the merge job.
  std::pair<std::string, std::string> Submit(const SingleNodeSlurm& slurm, const std::string& dir,
                                             const std::string& args = "") const {
    const Outcome submit = Shell(slurm.Env() + " " + dir + "/submit.sh " + args);
    EXPECT_EQ(submit.exit_code, 0) << submit.err;
    std::smatch m;
    const std::regex ids(R"(job array (\d+) .* merge job (\d+) into)");
    if (!std::regex_search(submit.out, m, ids)) {
      ADD_FAILURE() << "no job ids in: " << submit.out << submit.err;
      return {};
    }
    return {m[1].str(), m[2].str()};
  }
  // The serial sweep's study, computed once per test program (in the first test's folder).
  const std::string& Reference() {
    static std::optional<std::string> reference;
    if (!reference) {
      const Outcome run = Run("sweep plan.toml --out-dir serial --threads 1");
      EXPECT_EQ(run.exit_code, 0) << run.err;
      const Outcome merge = Run("sweep plan.toml --out-dir serial --merge");
      EXPECT_EQ(merge.exit_code, 0) << merge.err;
      reference = StudyFingerprint("serial.sqlite");
      EXPECT_GT(std::count(reference->begin(), reference->end(), '\n'), 20);  // steps stored
      EXPECT_TRUE(Contains(*reference, "runs: 4\n"));
      EXPECT_EQ(reference->find("no run"), std::string::npos);
    }
    return *reference;
  }
};

TEST_F(SweepClusterTest, MpirunTwoRanksGivesTheSerialStudyBitForBit) {
  const std::string& reference = Reference();
  const Outcome o =
      Run("sweep plan.toml --mpi", std::string(kMpiEnv) + " mpirun -n 2 --oversubscribe");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_TRUE(Contains(o.err, "4 line(s) of plan.toml on 2 rank(s), largest expected cost first"))
      << o.err;
  // Dispatched largest expected cost first: the two-node lines (1, 3) before the others.
  const std::regex dispatch(R"(line (\d) \([0-9a-f-]+, expected cost [^)]*\) to rank (\d))");
  std::vector<int> lines;
  std::vector<int> ranks;
  for (std::sregex_iterator it(o.err.begin(), o.err.end(), dispatch), end; it != end; ++it) {
    lines.push_back(std::stoi((*it)[1].str()));
    ranks.push_back(std::stoi((*it)[2].str()));
  }
  ASSERT_EQ(lines.size(), 4u) << o.err;
  EXPECT_EQ(lines, (std::vector<int>{1, 3, 0, 2})) << o.err;
  EXPECT_NE(std::find(ranks.begin(), ranks.end(), 0), ranks.end()) << o.err;  // both ranks ran
  EXPECT_NE(std::find(ranks.begin(), ranks.end(), 1), ranks.end()) << o.err;
  EXPECT_EQ(StudyFingerprint("runs.sqlite"), reference);

  // Run again: every line complete and skipped, the merge changes nothing.
  const Outcome again =
      Run("sweep plan.toml --mpi", std::string(kMpiEnv) + " mpirun -n 2 --oversubscribe");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_TRUE(Contains(again.err, "complete in runs/")) << again.err;
  EXPECT_TRUE(Contains(again.out, "0 run(s) copied, 1 already in runs.sqlite")) << again.out;
  EXPECT_EQ(StudyFingerprint("runs.sqlite"), reference);
}

// A rank killed with SIGKILL mid-sweep (mpirun then ends the job), and the sweep run again under
// mpirun: the lines complete before are skipped, the started ones continue, and the merged study
// is the serial one, nothing lost or doubled.
TEST_F(SweepClusterTest, MpiRankKilledThenRunAgainGivesTheSerialStudy) {
  const std::string& reference = Reference();
  Write("err.txt", "");
  const std::string err = (dir_ / "err.txt").string();
  const pid_t mpirun = fork();
  if (mpirun == 0) {
    setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
    setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
    const int fd = open(err.c_str(), O_WRONLY | O_APPEND);
    if (chdir(dir_.c_str()) != 0 || fd < 0) _exit(125);
    dup2(fd, 1);
    dup2(fd, 2);
    execlp("mpirun", "mpirun", "-n", "2", "--oversubscribe", RAILWEAR_BINARY, "sweep", "plan.toml",
           "--mpi", static_cast<char*>(nullptr));
    _exit(126);
  }
  ASSERT_GT(mpirun, 0);
  // Once a run has stored its second step, SIGKILL a rank (a child of mpirun).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!Contains(ReadFile(err), "railwear: step 2:") &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const Outcome ranks = Shell("pgrep -P " + std::to_string(mpirun));
  ASSERT_FALSE(ranks.out.empty()) << ReadFile(err);
  const pid_t rank = std::stoi(ranks.out);
  ASSERT_EQ(kill(rank, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(waitpid(mpirun, &status, 0), mpirun);
  EXPECT_FALSE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << ReadFile(err);
  int complete = 0;
  for (const std::string& id : Ids()) {
    const fs::path db = dir_ / "runs" / (id + ".sqlite");
    if (!fs::exists(db)) continue;
    const std::optional<RunInfo> run = ProfileStore::OpenReadOnly(db.string()).FindRun(id);
    complete += run && run->state == RunState::kComplete;
  }
  EXPECT_LT(complete, 4) << ReadFile(err);  // the kill cut the sweep short
  EXPECT_FALSE(fs::exists(dir_ / "runs.sqlite"));

  const Outcome again =
      Run("sweep plan.toml --mpi", std::string(kMpiEnv) + " mpirun -n 2 --oversubscribe");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(StudyFingerprint("runs.sqlite"), reference);
}

// A run that fails under MPI and records its failure (issue 19; kFailingSamplePlan's 0.0037 mm
// cell) is a result: rank 0 merges the two complete runs and the failed one, names it and exits
// 3, as the serial `sweep --merge` does.
TEST_F(SweepClusterTest, MpiRecordedRunFailureIsMergedAndNamedWithExitThree) {
  Write("fbase.toml", FailingSampleBase());
  Write("fail.toml", kFailingSamplePlan);
  const Outcome o =
      Run("sweep fail.toml --mpi", std::string(kMpiEnv) + " mpirun -n 2 --oversubscribe");
  EXPECT_EQ(o.exit_code, 3) << o.err;
  EXPECT_TRUE(Contains(o.out, "failed run: line ")) << o.out;
  EXPECT_TRUE(Contains(o.out, "model.cell_mm[0]=0.0036762220077216625")) << o.out;
  EXPECT_TRUE(Contains(o.err, "1 of 3 run(s) failed and are merged into")) << o.err;
  const ProfileStore study = ProfileStore::OpenReadOnly((dir_ / "fail_runs.sqlite").string());
  ASSERT_EQ(study.Runs().size(), 3u);
  int aborted = 0;
  for (const RunInfo& run : study.Runs()) {
    if (run.state == RunState::kAborted) {
      ++aborted;
      EXPECT_TRUE(
          Contains(study.FindRunFailure(run.id)->message, "the contact solution did not converge"));
    } else {
      EXPECT_EQ(run.state, RunState::kComplete) << run.name;
    }
  }
  EXPECT_EQ(aborted, 1);
}

// A line that fails under MPI (its database file is not SQLite) does not stop the others: rank 0
// names it with its rank and exit code, merges nothing and exits 1; with the file removed,
// mpirun again runs only that line and merges the serial study.
TEST_F(SweepClusterTest, MpiFailedLineLeavesTheOthersCompleteAndIsRunAgain) {
  const std::string& reference = Reference();
  const std::string bad = Ids()[2];
  fs::create_directories(dir_ / "runs");
  Write("runs/" + bad + ".sqlite", "not a database\n");
  const Outcome o =
      Run("sweep plan.toml --mpi", std::string(kMpiEnv) + " mpirun -n 2 --oversubscribe");
  EXPECT_EQ(o.exit_code, 1) << o.err;
  EXPECT_TRUE(Contains(o.err, "sweep line 2 (" + bad + "): database 'runs/" + bad +
                                  ".sqlite': not an SQLite database"))
      << o.err;
  EXPECT_TRUE(
      std::regex_search(o.err, std::regex(R"(1 of 4 line\(s\) failed: 2 \(rank [01], exit 2\))")))
      << o.err;
  EXPECT_FALSE(fs::exists(dir_ / "runs.sqlite"));
  for (const std::string& id : Ids()) {
    if (id == bad) continue;
    const ProfileStore store =
        ProfileStore::OpenReadOnly((dir_ / "runs" / (id + ".sqlite")).string());
    EXPECT_EQ(store.FindRun(id)->state, RunState::kComplete) << id;
  }
  fs::remove(dir_ / "runs" / (bad + ".sqlite"));
  const Outcome again =
      Run("sweep plan.toml --mpi", std::string(kMpiEnv) + " mpirun -n 2 --oversubscribe");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(StudyFingerprint("runs.sqlite"), reference);
}

TEST_F(SweepClusterTest, SlurmScriptsHoldTheArrayResourcesIndexLineAndDependentMerge) {
  const Outcome o = Run(
      "sweep plan.toml --slurm --cpus-per-task 2 --time 00:10:00 --mem 1500M --partition debug");
  ASSERT_EQ(o.exit_code, 0) << o.err;
  const std::string runs = fs::weakly_canonical(dir_ / "runs").string();
  const std::string array = ReadFile(dir_ / "runs/sweep.sbatch");
  for (const std::string& line :
       {std::string("#SBATCH --array=0-3\n"), std::string("#SBATCH --cpus-per-task=2\n"),
        std::string("#SBATCH --time=00:10:00\n"), std::string("#SBATCH --mem=1500M\n"),
        std::string("#SBATCH --partition=debug\n"),
        "#SBATCH --output=" + runs + "/logs/sweep_%A_%a.log\n",
        "sweep '" + fs::weakly_canonical(dir_ / "plan.toml").string() + "' --out-dir '" + runs +
            "' --threads \"${SLURM_CPUS_PER_TASK:-2}\" --index \"$SLURM_ARRAY_TASK_ID\"\n"}) {
    EXPECT_TRUE(Contains(array, line)) << line << " in\n" << array;
  }
  EXPECT_TRUE(
      Contains(ReadFile(dir_ / "runs/merge.sbatch"), "--merge --db '" + runs + ".sqlite'\n"));
  const std::string submit = ReadFile(dir_ / "runs/submit.sh");
  EXPECT_TRUE(Contains(submit, "array=$(sbatch --parsable \"$@\" '" + runs + "/sweep.sbatch')"));
  EXPECT_TRUE(Contains(
      submit, "sbatch --parsable --dependency=afterok:\"$array\" '" + runs + "/merge.sbatch'"));
  EXPECT_TRUE(fs::is_directory(dir_ / "runs/logs"));
  EXPECT_TRUE((fs::status(dir_ / "runs/submit.sh").permissions() & fs::perms::owner_exec) !=
              fs::perms::none);
  EXPECT_EQ(Run("sweep plan.toml --slurm").exit_code, 0);  // the defaults
  const std::string defaults = ReadFile(dir_ / "runs/sweep.sbatch");
  EXPECT_TRUE(Contains(defaults, "--cpus-per-task=1\n#SBATCH --time=01:00:00\n#SBATCH --mem=2G\n"))
      << defaults;
  EXPECT_FALSE(Contains(defaults, "--partition"));

  const Outcome time = Run("sweep plan.toml --slurm --time 1h");
  EXPECT_EQ(time.exit_code, 2);
  EXPECT_TRUE(Contains(time.err, "--time '1h': expected a Slurm time limit")) << time.err;
  const Outcome mem = Run("sweep plan.toml --slurm --mem 2GB");
  EXPECT_EQ(mem.exit_code, 2);
  EXPECT_TRUE(Contains(mem.err, "--mem '2GB': expected the memory of a task")) << mem.err;
  EXPECT_EQ(Run("sweep plan.toml --cpus-per-task 2").exit_code, 2);  // needs --slurm
  EXPECT_EQ(Run("sweep plan.toml --slurm --mpi").exit_code, 2);
  const Outcome db = Run("sweep plan.toml --db x.sqlite");
  EXPECT_EQ(db.exit_code, 2);
  EXPECT_TRUE(Contains(db.err, "expected one of them")) << db.err;
}

// Where Slurm is not at hand: the generated scripts' lines, run as Slurm would run them.
TEST_F(SweepClusterTest, SlurmArrayScriptLinesRunWithTaskIdGiveTheSerialStudyBitForBit) {
  const std::string& reference = Reference();
  ASSERT_EQ(Run("sweep plan.toml --slurm").exit_code, 0);
  for (const int task : {3, 0, 2}) {
    const Outcome o =
        Shell("SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " bash runs/sweep.sbatch");
    ASSERT_EQ(o.exit_code, 0) << o.err;
  }
  // Line 1 missing: the merge job refuses, names it and how to resubmit it, and writes nothing.
  const Outcome refused = Shell("bash runs/merge.sbatch");
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_TRUE(Contains(refused.err, "1 of 4 line(s) not complete")) << refused.err;
  EXPECT_TRUE(Contains(refused.err, "(not run: 1; started, not complete: none)"));
  EXPECT_TRUE(Contains(refused.err, "sbatch --array=1 "));
  EXPECT_FALSE(fs::exists(dir_ / "runs.sqlite"));
  const Outcome one = Shell("SLURM_ARRAY_TASK_ID=1 bash runs/sweep.sbatch");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const Outcome merged = Shell("bash runs/merge.sbatch");
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_EQ(StudyFingerprint("runs.sqlite"), reference);
}

TEST_F(SweepClusterTest, RealSingleNodeSlurmJobArrayGivesTheSerialStudyBitForBit) {
  SingleNodeSlurm slurm;
  if (const std::string why_not = StartOrWhyNot(&slurm); !why_not.empty()) GTEST_SKIP() << why_not;
  const std::string& reference = Reference();
  ASSERT_EQ(Run("sweep plan.toml --slurm --mem 200M --time 5").exit_code, 0);
  const auto [array, merge] = Submit(slurm, "runs");
  ASSERT_FALSE(array.empty());
  ASSERT_TRUE(slurm.WaitForEmptyQueue(std::chrono::seconds(180))) << slurm.Logs();
  EXPECT_EQ(slurm.JobState(merge), "COMPLETED") << slurm.Logs();
  for (int task = 0; task < 4; ++task) {
    const std::string log = "runs/logs/sweep_" + array + "_" + std::to_string(task) + ".log";
    EXPECT_TRUE(Contains(ReadFile(dir_ / log), "railwear: sweep line " + std::to_string(task)))
        << log;
  }
  EXPECT_EQ(StudyFingerprint("runs.sqlite"), reference);
}

// Past MaxArraySize: --max-array-size 3 cuts the 4 lines into two arrays (lines 0-2 and line
// 3, the second with RAILWEAR_SWEEP_OFFSET=3); the merge job waits for both.
TEST_F(SweepClusterTest, RealSingleNodeSlurmSlicedArraysGiveTheSerialStudyBitForBit) {
  SingleNodeSlurm slurm;
  if (const std::string why_not = StartOrWhyNot(&slurm); !why_not.empty()) GTEST_SKIP() << why_not;
  const std::string& reference = Reference();
  ASSERT_EQ(Run("sweep plan.toml --slurm --mem 200M --time 5 --max-array-size 3").exit_code, 0);
  const Outcome submit = Shell(slurm.Env() + " runs/submit.sh");
  ASSERT_EQ(submit.exit_code, 0) << submit.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(submit.out, m,
                                std::regex(R"(job array\(s\) (\d+):(\d+) .* merge job (\d+) into)")))
      << submit.out;
  const std::string first = m[1].str(), second = m[2].str(), merge = m[3].str();
  ASSERT_TRUE(slurm.WaitForEmptyQueue(std::chrono::seconds(180))) << slurm.Logs();
  EXPECT_EQ(slurm.JobState(merge), "COMPLETED") << slurm.Logs();
  // Task 0 of the second array ran line 3.
  EXPECT_TRUE(Contains(ReadFile(dir_ / ("runs/logs/sweep_" + second + "_0.log")),
                       "railwear: sweep line 3 "));
  EXPECT_TRUE(Contains(ReadFile(dir_ / ("runs/logs/sweep_" + first + "_2.log")),
                       "railwear: sweep line 2 "));
  EXPECT_EQ(StudyFingerprint("runs.sqlite"), reference);
}

// A Slurm array task killed with SIGKILL mid-run (its processes, from scontrol listpids), its
// merge job left pending (afterok never satisfied), the line resubmitted by index with
// submit.sh --array=0: the run continues, the new merge job runs, and the study holds exactly
// the run an uninterrupted `wear` of the line's scene stores, once.
TEST_F(SweepClusterTest, RealSlurmTaskKilledThenResubmittedByIndexMergesNothingLostOrDoubled) {
  SingleNodeSlurm slurm;
  if (const std::string why_not = StartOrWhyNot(&slurm); !why_not.empty()) GTEST_SKIP() << why_not;
  // One line of 1e5 passes: 10 steps, long enough to be killed after its second.
  Write("long.toml", SmallStudyOfPasses("1e5"));
  Write("one.toml",
        "[sweep]\nscene = \"long.toml\"\nout_dir = \"one\"\n[[axis]]\nkey = \"wear.k\"\n"
        "values = [2.0e-4]\n");
  ASSERT_EQ(Run("sweep one.toml --slurm --mem 200M --time 5").exit_code, 0);
  const std::string id = Run("sweep one.toml --list").out.substr(0, 13);
  const auto [array, merge_job] = Submit(slurm, "one");
  ASSERT_FALSE(array.empty());
  const std::string task = array + "_0";
  const fs::path log = dir_ / "one/logs" / ("sweep_" + task + ".log");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!Contains(ReadFile(log), "railwear: step 2:") &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(Contains(ReadFile(log), "railwear: step 2:")) << slurm.Logs();
  // SIGKILL to the task's processes themselves (`scancel --signal=KILL` would cancel the job:
  // SIGTERM first, SIGKILL only after KillWait).
  const std::string job_id = Shell(slurm.Env() + " squeue -h -j " + task + " -o %A").out;
  const Outcome pids =
      Shell(slurm.Env() + " scontrol listpids " + job_id.substr(0, job_id.find('\n')) +
            " | awk 'NR > 1 && $1 ~ /^[0-9]+$/ { print $1 }'");
  ASSERT_FALSE(pids.out.empty()) << pids.err << slurm.Logs();
  std::istringstream pid_list(pids.out);
  for (std::string pid; pid_list >> pid;) EXPECT_EQ(kill(std::stoi(pid), SIGKILL), 0) << pid;
  // The task ends; the merge job waits for a dependency that can no longer be satisfied.
  const auto never = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  std::string reason;
  while (std::chrono::steady_clock::now() < never) {
    reason = Shell(slurm.Env() + " squeue -h -j " + merge_job + " -o %r").out;
    if (Contains(reason, "DependencyNeverSatisfied")) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(250));
  }
  ASSERT_TRUE(Contains(reason, "DependencyNeverSatisfied")) << reason << slurm.Logs();
  {
    const ProfileStore cut = ProfileStore::OpenReadOnly((dir_ / "one" / (id + ".sqlite")).string());
    EXPECT_EQ(cut.FindRun(id)->state, RunState::kRunning);  // killed: no state written
  }
  EXPECT_FALSE(fs::exists(dir_ / "one.sqlite"));

  ASSERT_EQ(Shell(slurm.Env() + " scancel " + merge_job).exit_code, 0);
  const std::string again = Submit(slurm, "one", "--array=0").first;
  ASSERT_FALSE(again.empty());
  ASSERT_TRUE(slurm.WaitForEmptyQueue(std::chrono::seconds(180))) << slurm.Logs();
  const std::string resumed = ReadFile(dir_ / "one/logs" / ("sweep_" + again + "_0.log"));
  EXPECT_TRUE(Contains(resumed, "sweep line 0 (" + id + "): wear.k=0.0002 (continued)")) << resumed;

  const Outcome whole =
      Run("wear one/" + id + ".toml --db whole.sqlite --run " + id + " --threads 1");
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const std::string expected = RunFingerprint(dir_ / "whole.sqlite", id);
  ASSERT_NE(expected, "no run");
  EXPECT_EQ(RunFingerprint(dir_ / "one.sqlite", id), expected);
  EXPECT_EQ(ProfileStore::OpenReadOnly((dir_ / "one.sqlite").string()).Runs().size(), 1u);
}

}  // namespace
}  // namespace railwear::test
