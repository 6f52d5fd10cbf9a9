// Test helper: a real single-node Slurm cluster on localhost for the sweep's job-array test
// (issue 19): munged, slurmctld and slurmd started as child processes in the foreground, from a
// minimal slurm.conf in a fresh temporary folder (its own ports, state, spool, logs and munge
// key: nothing of the machine's own Slurm or munge is used or touched), and stopped (SIGTERM,
// then SIGKILL) when the object goes.
//
// Container-friendly settings: proctrack/linuxproc, task/none, no cgroups, no accounting, and
// slurmd's configuration taken from slurm.conf (config_overrides). Start() returns an empty
// string when the cluster is up (the node idle), else why not, with the daemons' log tails:
// the caller skips with it (GTEST_SKIP), so the test runs wherever Slurm can start.
#pragma once

#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "tests/test_support.h"

namespace railwear::test {

class SingleNodeSlurm {
 public:
  SingleNodeSlurm() = default;
  SingleNodeSlurm(const SingleNodeSlurm&) = delete;
  SingleNodeSlurm& operator=(const SingleNodeSlurm&) = delete;
  ~SingleNodeSlurm() { Stop(); }

  // Starts the daemons; "" when the node is idle within `timeout`, else the reason.
  std::string Start(std::chrono::seconds timeout = std::chrono::seconds(40)) {
    for (const char* tool : {"munged", "slurmctld", "slurmd", "sbatch", "sinfo"}) {
      if (Shell(std::string("command -v ") + tool + " > /dev/null 2>&1") != 0) {
        return std::string(tool) +
               " is not installed (Debian: slurmctld slurmd slurm-client munge, "
               ".ci/install-deps.sh)";
      }
    }
    // A short folder: munge's and slurmd's Unix sockets must fit in 108 characters.
    char dir_template[] = "/tmp/rwslurm.XXXXXX";
    if (mkdtemp(dir_template) == nullptr) return "mkdtemp failed";
    dir_ = dir_template;
    for (const char* sub : {"munge", "state", "spool", "log"}) {
      std::filesystem::create_directories(dir_ / sub);
    }
    std::filesystem::permissions(dir_ / "munge", std::filesystem::perms::owner_all);
    std::string key(1024, '\0');
    std::ifstream("/dev/urandom", std::ios::binary).read(key.data(), 1024);
    std::ofstream(dir_ / "munge/munge.key", std::ios::binary) << key;
    std::filesystem::permissions(dir_ / "munge/munge.key", std::filesystem::perms::owner_read |
                                                               std::filesystem::perms::owner_write);
    const std::string user = Output("id -un");
    const std::string d = dir_.string();
    const unsigned cpus = std::max(1u, std::thread::hardware_concurrency());
    const std::pair<int, int> ports = FreePorts();
    std::ostringstream conf;
    conf << "ClusterName=railwear-test\n"
         << "SlurmctldHost=localhost\n"
         << "SlurmUser=" << user << "\nSlurmdUser=" << user << "\n"
         << "SlurmctldPort=" << ports.first << "\nSlurmdPort=" << ports.second << "\n"
         << "AuthType=auth/munge\nCredType=cred/munge\n"
         << "AuthInfo=socket=" << d << "/munge/munge.socket\n"
         << "StateSaveLocation=" << d << "/state\nSlurmdSpoolDir=" << d << "/spool\n"
         << "SlurmctldPidFile=" << d << "/slurmctld.pid\nSlurmdPidFile=" << d << "/slurmd.pid\n"
         << "SlurmctldLogFile=" << d << "/log/slurmctld.log\n"
         << "SlurmdLogFile=" << d << "/log/slurmd.log\n"
         << "ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\n"
         << "JobAcctGatherType=jobacct_gather/none\n"
         << "AccountingStorageType=accounting_storage/none\n"
         << "SwitchType=switch/none\nMpiDefault=none\n"
         << "SchedulerType=sched/builtin\n"
         << "SelectType=select/cons_tres\nSelectTypeParameters=CR_Core\n"
         << "SlurmdParameters=config_overrides\nReturnToService=2\n"
         << "NodeName=localhost NodeHostname=localhost NodeAddr=127.0.0.1 CPUs=" << cpus
         << " RealMemory=1000 State=UNKNOWN\n"
         << "PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP\n";
    std::ofstream(dir_ / "slurm.conf") << conf.str();
    conf_ = (dir_ / "slurm.conf").string();

    Spawn({"munged", "-F", "-f", "--socket=" + d + "/munge/munge.socket",
           "--key-file=" + d + "/munge/munge.key", "--log-file=" + d + "/log/munged.log",
           "--pid-file=" + d + "/munge/munged.pid", "--seed-file=" + d + "/munge/munged.seed"},
          "munged");
    if (!WaitFor([&] { return std::filesystem::exists(dir_ / "munge/munge.socket"); },
                 std::chrono::seconds(10))) {
      return "munged did not start:\n" + Logs();
    }
    Spawn({"slurmctld", "-D", "-c", "-f", conf_}, "slurmctld");
    Spawn({"slurmd", "-D", "-N", "localhost", "-f", conf_}, "slurmd");
    const bool idle = WaitFor(
        [&] { return Exited().empty() && Output(Env() + " sinfo -h -o %T 2>/dev/null") == "idle"; },
        timeout);
    if (!idle) {
      const std::string exited = Exited();
      return (exited.empty() ? "the node did not become idle in time"
                             : "a daemon exited: " + exited) +
             ":\n" + Logs();
    }
    return "";
  }

  // "SLURM_CONF=FILE": the prefix of a shell command for this cluster.
  std::string Env() const { return "SLURM_CONF='" + conf_ + "'"; }

  // Waits until no job is left in the queue; false after `timeout`.
  bool WaitForEmptyQueue(std::chrono::seconds timeout) const {
    return WaitFor([&] { return Output(Env() + " squeue -h -o %i 2>&1").empty(); }, timeout);
  }

  // `scontrol show job ID`'s JobState ("COMPLETED", "FAILED", ...).
  std::string JobState(const std::string& id) const {
    return Output(Env() + " scontrol show job " + id +
                  " 2>&1 | grep -o 'JobState=[A-Z_]*' | head -1 | cut -d= -f2");
  }

  // The daemons' logs (their last lines), for a failure message.
  std::string Logs() const {
    std::string out;
    for (const char* log : {"munged.out", "slurmctld.out", "slurmd.out"}) {
      out += std::string("--- ") + log + " (last lines):\n" +
             Output("tail -n 15 '" + (dir_ / "log" / log).string() + "' 2>&1") + "\n";
    }
    return out;
  }

  // Cancels every job, then stops the daemons (SIGTERM; SIGKILL after 10 s) and removes the
  // folder.
  void Stop() {
    if (!conf_.empty() && Exited().empty()) Shell(Env() + " scancel --user=$(id -un) 2>/dev/null");
    for (auto it = children_.rbegin(); it != children_.rend(); ++it) {
      if (it->pid <= 0) continue;
      kill(it->pid, SIGTERM);
      const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(10);
      int status = 0;
      while (waitpid(it->pid, &status, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() > end) {
          kill(it->pid, SIGKILL);
          waitpid(it->pid, &status, 0);
          break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
      it->pid = -1;
    }
    children_.clear();
    if (!dir_.empty()) {
      std::error_code ec;
      std::filesystem::remove_all(dir_, ec);
      dir_.clear();
    }
  }

 private:
  struct Child {
    std::string name;
    pid_t pid = -1;
  };

  static int Shell(const std::string& command) { return std::system(command.c_str()); }

  // A command's stdout, trailing whitespace removed.
  static std::string Output(const std::string& command) {
    std::string out;
    if (FILE* p = popen(command.c_str(), "r")) {
      char buffer[4096];
      for (size_t n; (n = fread(buffer, 1, sizeof buffer, p)) > 0;) out.append(buffer, n);
      pclose(p);
    }
    while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
    return out;
  }

  // Two TCP ports free now on localhost (the kernel's picks for port 0, both sockets open at
  // once so that the two differ).
  static std::pair<int, int> FreePorts() {
    int ports[2] = {0, 0};
    int sockets[2] = {-1, -1};
    for (int i = 0; i < 2; ++i) {
      sockets[i] = socket(AF_INET, SOCK_STREAM, 0);
      sockaddr_in a{};
      a.sin_family = AF_INET;
      a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
      a.sin_port = 0;
      socklen_t len = sizeof a;
      bind(sockets[i], reinterpret_cast<sockaddr*>(&a), sizeof a);
      getsockname(sockets[i], reinterpret_cast<sockaddr*>(&a), &len);
      ports[i] = ntohs(a.sin_port);
    }
    for (const int s : sockets) close(s);
    return {ports[0], ports[1]};
  }

  template <class Ready>
  static bool WaitFor(Ready ready, std::chrono::seconds timeout) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
      if (ready()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(250));
    }
    return ready();
  }

  // Starts `args` (found on PATH) with stdout and stderr to log/NAME.out.
  void Spawn(const std::vector<std::string>& args, const std::string& name) {
    const std::string log = (dir_ / "log" / (name + ".out")).string();
    std::vector<std::string> text = args;
    std::vector<char*> argv;
    for (std::string& a : text) argv.push_back(a.data());
    argv.push_back(nullptr);
    const std::string conf = "SLURM_CONF=" + conf_;
    const pid_t pid = fork();
    if (pid == 0) {
      putenv(const_cast<char*>(conf.c_str()));
      const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (fd < 0) _exit(125);
      dup2(fd, 1);
      dup2(fd, 2);
      execvp(argv[0], argv.data());
      _exit(126);
    }
    children_.push_back({name, pid});
  }

  // The daemons that have exited, with their exit status ("slurmd (exit 1) "); "" for none.
  std::string Exited() {
    for (Child& c : children_) {
      int status = 0;
      if (c.pid > 0 && waitpid(c.pid, &status, WNOHANG) == c.pid) {
        exited_ += c.name +
                   (WIFEXITED(status) ? " (exit " + std::to_string(WEXITSTATUS(status))
                                      : " (signal " + std::to_string(WTERMSIG(status))) +
                   ") ";
        c.pid = -1;
      }
    }
    return exited_;
  }

  std::filesystem::path dir_;
  std::string conf_;
  std::vector<Child> children_;
  std::string exited_;  // the daemons seen exited, with their status
};

}  // namespace railwear::test
