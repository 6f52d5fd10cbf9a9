// External programs of the FEM pipeline (gmsh, CalculiX ccx): finding them on PATH or through an
// environment override, and running one by argv (fork/exec, no shell) in a work directory with
// its output captured in a log file, timed by the wall clock.
//
// A program that is not installed is bad input (InputError, exit code 2 in the CLI) with a
// message that says how to install it; a program that runs and fails is a runtime failure
// (RunProgramOrThrow throws std::runtime_error quoting the end of its log).
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace railwear {

// How to find one external program and what to tell the user when it is missing.
struct ProgramSpec {
  std::string name;          // executable name looked up on PATH, e.g. "ccx"
  std::string env_override;  // environment variable that names the executable, e.g. "RAILWEAR_CCX"
  std::string description;   // for messages, e.g. "ccx (CalculiX)"
  std::string install_hint;  // e.g. "install the Debian package calculix-ccx (...)"
};

// CalculiX (`ccx`, Debian package calculix-ccx; override RAILWEAR_CCX) and gmsh (`gmsh`, Debian
// package gmsh; override RAILWEAR_GMSH).
ProgramSpec CcxProgram();
ProgramSpec GmshProgram();

// The executable's path: the value of spec.env_override when that variable is set and not empty
// (a path, or a name looked up on PATH), otherwise spec.name looked up on PATH. Throws
// InputError when it is not an executable file, e.g. "ccx (CalculiX) is not installed or not on
// PATH: install the Debian package calculix-ccx (bash .ci/install-deps.sh), or set RAILWEAR_CCX".
std::string FindProgram(const ProgramSpec& spec);

// `name` looked up in the directories of PATH (a name with a '/' is taken as a path); empty when
// there is no executable regular file of that name.
std::string FindOnPath(const std::string& name);

struct ProgramRun {
  // argv[0] is the executable (a path, or a name looked up on PATH); never empty.
  std::vector<std::string> argv;
  std::string work_dir = ".";  // the child's working directory (must exist)
  // stdout and stderr of the child go to this file (truncated first); a relative path is
  // relative to work_dir.
  std::string log_path = "program.log";
  // Variables set (or replaced) in the child's environment, on top of the parent's.
  std::vector<std::pair<std::string, std::string>> environment;
  // Wall-clock limit [s]; the child is killed (SIGKILL) when it runs longer. 0: no limit.
  double timeout_s = 0.0;
};

struct ProgramResult {
  enum class Status { kExited, kSignaled, kTimedOut };
  Status status = Status::kExited;
  int exit_code = -1;        // for kExited; 127 when the program could not be executed
  int signal = 0;            // for kSignaled
  double wall_time_s = 0.0;  // from start to exit
  std::string log_path;      // the log file (work_dir joined with ProgramRun::log_path)

  bool Succeeded() const { return status == Status::kExited && exit_code == 0; }
  // "exit code 2", "killed by signal 11", "timed out after 5.0 s".
  std::string Describe() const;
};

// Runs the program and waits for it. Throws std::runtime_error when the log file cannot be
// created or the process cannot be started; a program that cannot be executed (no such file,
// not executable) exits with code 127 and says why in its log. Safe to call from several
// threads at once (each call starts its own child).
ProgramResult RunProgram(const ProgramRun& run);

// Runs the program; when it does not succeed, throws std::runtime_error with
// ProgramFailureMessage(what, result.Describe(), ...).
ProgramResult RunProgramOrThrow(const ProgramRun& run, std::string_view what);

// "WHAT failed (REASON) after 1.2 s in WORK_DIR; log LOG_PATH ends with:\n<its last 15 lines>".
std::string ProgramFailureMessage(std::string_view what, std::string_view reason,
                                  const std::string& work_dir, const ProgramResult& result);

// The last `max_lines` lines of a text file (at most the last 64 KiB of it); empty when it
// cannot be read.
std::string LogTail(const std::string& path, int max_lines);

}  // namespace railwear
