// Test tool (LD_PRELOAD shim, built only in the test tree): kills the process with a real SIGKILL
// at its N-th fsync or fdatasync, before that call runs, so a test can stop `railwear wear` at
// every durability point of SQLite's commits (issue 17: "a kill at each fsync").
//
//   RAILWEAR_KILL_AT_FSYNC=N   raise(SIGKILL) on the N-th call (1-based); unset or 0: never
//   RAILWEAR_FSYNC_LOG=FILE    append one line per call: "N fsync|fdatasync PATH"
//
// Both calls are counted together, in the order the process makes them. The railwear binary has
// no test hook: the shim only wraps the C library's functions (dlsym(RTLD_NEXT)).
#ifndef _GNU_SOURCE
#define _GNU_SOURCE
#endif
#include <dlfcn.h>
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

std::atomic<long> g_calls{0};

long EnvNumber(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::strtol(v, nullptr, 10) : 0;
}

// Counts the call, logs it, and kills the process when it is the N-th.
void BeforeSync(const char* function, int fd) {
  const long n = ++g_calls;
  if (const char* log = std::getenv("RAILWEAR_FSYNC_LOG")) {
    char link[64], target[512] = "?";
    std::snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
    const ssize_t len = readlink(link, target, sizeof target - 1);
    if (len > 0) target[len] = '\0';
    char line[640];
    const int size = std::snprintf(line, sizeof line, "%ld %s %s\n", n, function, target);
    const int out = open(log, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (out >= 0) {
      if (write(out, line, static_cast<size_t>(size)) < 0) {
      }
      close(out);
    }
  }
  if (n == EnvNumber("RAILWEAR_KILL_AT_FSYNC")) raise(SIGKILL);
}

template <typename F>
F Next(const char* name) {
  return reinterpret_cast<F>(dlsym(RTLD_NEXT, name));
}

}  // namespace

extern "C" int fsync(int fd) {
  static const auto real = Next<int (*)(int)>("fsync");
  BeforeSync("fsync", fd);
  return real(fd);
}

extern "C" int fdatasync(int fd) {
  static const auto real = Next<int (*)(int)>("fdatasync");
  BeforeSync("fdatasync", fd);
  return real(fd);
}
