#include "swlio/daemon/runtime/thread_setup.h"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <fstream>

#include <cstring>

namespace swlio::daemon {
namespace {

std::string Failure(const char* name, const char* what, int err) {
  return std::string(name) + ": " + what + " failed: " + std::strerror(err);
}

/// Linux keeps the nice value per thread (pthreads(7)): setpriority on the thread's id.
void SetNice(const char* name, int64_t nice, std::vector<std::string>* problems) {
  if (setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), static_cast<int>(nice)) != 0) {
    problems->push_back(Failure(name, ("nice " + std::to_string(nice)).c_str(), errno));
  }
}

void Pin(const char* name, int64_t cpu, std::vector<std::string>* problems) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(static_cast<size_t>(cpu), &set);
  if (const int err = pthread_setaffinity_np(pthread_self(), sizeof set, &set); err != 0) {
    problems->push_back(Failure(name, ("pinning to CPU " + std::to_string(cpu)).c_str(), err));
  }
}

/// Whether the process holds CAP_SYS_NICE (bit 23 of CapEff in /proc/self/status, proc(5)).
bool HoldsCapSysNice() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("CapEff:", 0) != 0) continue;
    const unsigned long long caps = std::strtoull(line.c_str() + 7, nullptr, 16);
    return ((caps >> 23) & 1ULL) != 0;
  }
  return false;
}

/// SCHED_FIFO at `priority`: allowed with CAP_SYS_NICE, or without any capability up to
/// RLIMIT_RTPRIO (sched(7); swliod.service sets LimitRTPRIO), unless the kernel has
/// CONFIG_RT_GROUP_SCHED and the thread's cpu cgroup no real-time budget. Empty on success,
/// else what failed and which of these it was.
std::string SetFifo(const char* name, int64_t priority) {
  sched_param p{};
  p.sched_priority = static_cast<int>(priority);
  const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p);
  if (err == 0) return {};
  rlimit limit{};
  getrlimit(RLIMIT_RTPRIO, &limit);
  const bool allowed = HoldsCapSysNice() || limit.rlim_cur >= static_cast<rlim_t>(priority);
  return Failure(name, ("SCHED_FIFO " + std::to_string(priority)).c_str(), err) +
         (allowed ? " (permitted, so the cpu cgroup has no real-time budget: docs/scheduling.md)"
                  : " (RLIMIT_RTPRIO " + std::to_string(limit.rlim_cur) + ", no CAP_SYS_NICE)");
}

}  // namespace

std::vector<std::string> SetUpThisThread(const char* name, const RealtimeConfig& config) {
  std::vector<std::string> problems;
  pthread_setname_np(pthread_self(), name);
  for (const ThreadSchedConfig& t : config.threads) {
    if (t.name != name) continue;
    bool fifo = config.enabled && t.priority > 0;
    if (fifo) {
      if (std::string problem = SetFifo(name, t.priority); !problem.empty()) {
        problems.push_back(problem + "; nice " + std::to_string(t.nice) + " instead");
        fifo = false;
      }
    }
    if (t.nice != 0 && !fifo) SetNice(name, t.nice, &problems);
    if (config.enabled && t.cpu >= 0) Pin(name, t.cpu, &problems);
  }
  return problems;
}

std::string LockMemory(const RealtimeConfig& config) {
  if (!config.lock_memory) return {};
  if (mlockall(MCL_CURRENT | MCL_FUTURE) != 0) return Failure("process", "mlockall", errno);
  return {};
}

}  // namespace swlio::daemon
