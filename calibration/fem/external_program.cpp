// Finding and running external programs (gmsh, ccx) by argv. See external_program.h.
#include "calibration/fem/external_program.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>

#include "core/numerics/input_error.h"

extern char** environ;

namespace railwear {
namespace {

constexpr int kExitCannotExecute = 127;  // the shell's convention for "command not found"

bool IsExecutableFile(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

// "NAME=VALUE" strings: the parent's environment with `overrides` set or replaced.
std::vector<std::string> ChildEnvironment(
    const std::vector<std::pair<std::string, std::string>>& overrides) {
  std::vector<std::string> env;
  for (char** e = environ; e != nullptr && *e != nullptr; ++e) {
    const std::string_view entry(*e);
    const std::string_view name = entry.substr(0, entry.find('='));
    bool replaced = false;
    for (const auto& [key, value] : overrides) replaced = replaced || name == key;
    if (!replaced) env.emplace_back(entry);
  }
  for (const auto& [key, value] : overrides) env.push_back(key + "=" + value);
  return env;
}

std::vector<char*> CPointers(std::vector<std::string>& strings) {
  std::vector<char*> out;
  out.reserve(strings.size() + 1);
  for (std::string& s : strings) out.push_back(s.data());
  out.push_back(nullptr);
  return out;
}

// Writes a message to fd from the forked child (async-signal-safe: write only).
void ChildMessage(int fd, const char* a, const char* b, const char* c) {
  for (const char* s : {a, b, c}) {
    if (s != nullptr) {
      const ssize_t ignored = ::write(fd, s, std::strlen(s));
      (void)ignored;
    }
  }
}

}  // namespace

ProgramSpec CcxProgram() {
  return {"ccx", "RAILWEAR_CCX", "ccx (CalculiX)",
          "install the Debian package calculix-ccx (bash .ci/install-deps.sh)"};
}

ProgramSpec GmshProgram() {
  return {"gmsh", "RAILWEAR_GMSH", "gmsh",
          "install the Debian package gmsh (bash .ci/install-deps.sh)"};
}

std::string FindOnPath(const std::string& name) {
  if (name.empty()) return "";
  if (name.find('/') != std::string::npos) return IsExecutableFile(name) ? name : "";
  const char* path = std::getenv("PATH");
  if (path == nullptr) return "";
  std::string_view dirs(path);
  while (true) {
    const size_t colon = dirs.find(':');
    const std::string_view dir = dirs.substr(0, colon);
    const std::string candidate = (dir.empty() ? std::string(".") : std::string(dir)) + "/" + name;
    if (IsExecutableFile(candidate)) return candidate;
    if (colon == std::string_view::npos) return "";
    dirs.remove_prefix(colon + 1);
  }
}

std::string FindProgram(const ProgramSpec& spec) {
  const char* override_value =
      spec.env_override.empty() ? nullptr : std::getenv(spec.env_override.c_str());
  if (override_value != nullptr && *override_value != '\0') {
    const std::string found = FindOnPath(override_value);
    if (found.empty()) {
      throw InputError(
          fmt::format("{} not found: environment variable {} = '{}' is not an "
                      "executable file; expected the path of the {} executable "
                      "(or unset {} to look for '{}' on PATH)",
                      spec.description, spec.env_override, override_value, spec.name,
                      spec.env_override, spec.name));
    }
    return found;
  }
  const std::string found = FindOnPath(spec.name);
  if (found.empty()) {
    throw InputError(
        fmt::format("{} is not installed or not on PATH: {}, or set {} to the path "
                    "of the '{}' executable",
                    spec.description, spec.install_hint, spec.env_override, spec.name));
  }
  return found;
}

std::string ProgramResult::Describe() const {
  switch (status) {
    case Status::kExited:
      return exit_code == kExitCannotExecute ? "exit code 127 (could not be executed)"
                                             : fmt::format("exit code {}", exit_code);
    case Status::kSignaled:
      return fmt::format("killed by signal {}", signal);
    case Status::kTimedOut:
      return fmt::format("timed out after {:.1f} s", wall_time_s);
  }
  return "?";
}

ProgramResult RunProgram(const ProgramRun& run) {
  namespace fs = std::filesystem;
  if (run.argv.empty()) throw std::runtime_error("RunProgram: empty argv");
  ProgramResult result;
  const fs::path log = fs::path(run.work_dir) / run.log_path;
  result.log_path = log.string();

  // Everything the child needs is prepared before fork: after it, only async-signal-safe calls.
  std::string executable = FindOnPath(run.argv[0]);
  if (executable.empty()) executable = run.argv[0];  // exec fails and says so in the log
  std::vector<std::string> argv_strings = run.argv;
  std::vector<char*> argv = CPointers(argv_strings);
  std::vector<std::string> env_strings = ChildEnvironment(run.environment);
  std::vector<char*> envp = CPointers(env_strings);
  const std::string work_dir = run.work_dir;

  const int log_fd =
      ::open(result.log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (log_fd < 0) {
    throw std::runtime_error(
        fmt::format("cannot create the log file {}: {}", result.log_path, std::strerror(errno)));
  }
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int err = errno;
    ::close(log_fd);
    throw std::runtime_error(
        fmt::format("cannot start {}: fork failed: {}", run.argv[0], std::strerror(err)));
  }
  if (pid == 0) {  // child
    const int null_fd = ::open("/dev/null", O_RDONLY);
    if (null_fd >= 0) ::dup2(null_fd, STDIN_FILENO);
    ::dup2(log_fd, STDOUT_FILENO);
    ::dup2(log_fd, STDERR_FILENO);
    if (::chdir(work_dir.c_str()) != 0) {
      ChildMessage(STDERR_FILENO, "cannot change to the work directory ", work_dir.c_str(), "\n");
      ::_exit(kExitCannotExecute);
    }
    ::execve(executable.c_str(), argv.data(), envp.data());
    ChildMessage(STDERR_FILENO, "cannot execute ", executable.c_str(), ": ");
    ChildMessage(STDERR_FILENO, std::strerror(errno), "\n", nullptr);
    ::_exit(kExitCannotExecute);
  }
  ::close(log_fd);

  int status = 0;
  auto poll_interval = std::chrono::microseconds(500);
  while (true) {
    const pid_t done = ::waitpid(pid, &status, run.timeout_s > 0.0 ? WNOHANG : 0);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) {
      throw std::runtime_error(
          fmt::format("waiting for {} failed: {}", run.argv[0], std::strerror(errno)));
    }
    if (done == 0) {  // still running (only with a timeout)
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (elapsed > run.timeout_s) {
        ::kill(pid, SIGKILL);
        ::waitpid(pid, &status, 0);
        result.status = ProgramResult::Status::kTimedOut;
        result.wall_time_s = elapsed;
        return result;
      }
      std::this_thread::sleep_for(poll_interval);
      poll_interval = std::min(poll_interval * 2, std::chrono::microseconds(20000));
    }
  }
  result.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (WIFEXITED(status)) {
    result.status = ProgramResult::Status::kExited;
    result.exit_code = WEXITSTATUS(status);
  } else {
    result.status = ProgramResult::Status::kSignaled;
    result.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  }
  return result;
}

ProgramResult RunProgramOrThrow(const ProgramRun& run, std::string_view what) {
  const ProgramResult result = RunProgram(run);
  if (!result.Succeeded()) {
    throw std::runtime_error(ProgramFailureMessage(what, result.Describe(), run.work_dir, result));
  }
  return result;
}

std::string ProgramFailureMessage(std::string_view what, std::string_view reason,
                                  const std::string& work_dir, const ProgramResult& result) {
  constexpr int kTailLines = 15;
  return fmt::format("{} failed ({}) after {:.1f} s in {}; log {} ends with:\n{}", what, reason,
                     result.wall_time_s, work_dir, result.log_path,
                     LogTail(result.log_path, kTailLines));
}

std::string LogTail(const std::string& path, int max_lines) {
  constexpr std::streamoff kMaxBytes = 64 * 1024;
  std::ifstream in(path, std::ios::binary);
  if (!in || max_lines <= 0) return "";
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  const std::streamoff start = size > kMaxBytes ? size - kMaxBytes : 0;
  in.seekg(start);
  std::deque<std::string> lines;
  std::string line;
  bool first = start > 0;  // a partial line at the cut
  while (std::getline(in, line)) {
    if (first) {
      first = false;
      continue;
    }
    lines.push_back(line);
    if (static_cast<int>(lines.size()) > max_lines) lines.pop_front();
  }
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  return out;
}

}  // namespace railwear
