#include "swlio/daemon/runtime/thread_setup.h"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>

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

}  // namespace

std::vector<std::string> SetUpThisThread(const char* name, const RealtimeConfig& config) {
  std::vector<std::string> problems;
  pthread_setname_np(pthread_self(), name);
  for (const ThreadSchedConfig& t : config.threads) {
    if (t.name != name) continue;
    const bool fifo = config.enabled && t.priority > 0;
    if (t.nice != 0 && !fifo) SetNice(name, t.nice, &problems);
    if (!config.enabled) continue;
    if (t.priority > 0) {
      sched_param p{};
      p.sched_priority = static_cast<int>(t.priority);
      if (const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p); err != 0) {
        problems.push_back(Failure(name, "SCHED_FIFO", err));
      }
    }
    if (t.cpu >= 0) {
      cpu_set_t set;
      CPU_ZERO(&set);
      CPU_SET(static_cast<size_t>(t.cpu), &set);
      if (const int err = pthread_setaffinity_np(pthread_self(), sizeof set, &set); err != 0) {
        problems.push_back(Failure(name, ("pinning to CPU " + std::to_string(t.cpu)).c_str(), err));
      }
    }
  }
  return problems;
}

std::string LockMemory(const RealtimeConfig& config) {
  if (!config.lock_memory) return {};
  if (mlockall(MCL_CURRENT | MCL_FUTURE) != 0) return Failure("process", "mlockall", errno);
  return {};
}

}  // namespace swlio::daemon
