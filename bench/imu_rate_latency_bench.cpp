// IMU-rate output latency while the optimizer runs (issue 6: p99 ≤ 1 ms from IMU sample to
// output). Not a Google Benchmark: a real-time program with its own main (which takes
// precedence over the one in libbenchmark_main.a), three threads as in design.md:
//   imu producer  – every 2.5 ms (clock_nanosleep on CLOCK_MONOTONIC, absolute) stamps a sample
//                   of a constant-rate level turn and pushes it into an SPSC queue;
//   propagator    – blocks on that queue, runs ImuRatePropagator::Add and takes the output time
//                   at once (latency = output time − the sample's enqueue time); between
//                   samples it applies the optimized states waiting in a second SPSC queue;
//   optimizer     – every 100 ms (one sweep) does estimator work for --work-ms of its own CPU
//                   time, then pushes the state at that sweep's end time. The tightly coupled
//                   window is not there yet, so the work is the LiDAR-only per-sweep pipeline
//                   (FrontEnd + ScanMatcher against a VoxelMap, ≈ 7 ms on one core) repeated on
//                   successive simulated sweeps until the CPU budget is spent.
// By default nothing is pinned and no real-time priority is asked for: the figure is what a plain
// SCHED_OTHER process gets on the machine as it is (its load average is printed). --fifo P gives
// the producer and propagator threads SCHED_FIFO priority P, as systemd/swliod-realtime.conf
// allows the daemon.
//
//   swlio_imu_rate_latency_bench [--seconds 30] [--work-ms 30] [--optimizer-nice 0] [--fifo 0]

#include <pthread.h>
#include <readerwriterqueue.h>
#include <sched.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "labelled_scan.h"
#include "sim_setup.h"
#include "swlio/core/time.h"
#include "swlio/estimator/front_end.h"
#include "swlio/estimator/imu_rate_propagator.h"
#include "swlio/estimator/scan_matcher.h"
#include "swlio/estimator/voxel_map.h"

namespace {

using namespace swlio;             // NOLINT(google-build-using-namespace): bench file only
using namespace swlio::estimator;  // NOLINT(google-build-using-namespace)

constexpr double kG = 9.80665, kSpeedMps = 1.5, kYawRateRadps = 0.5;
constexpr int64_t kImuPeriodNs = 2'500'000;         // 400 Hz
constexpr int64_t kSweepPeriodNs = 100 * kNsPerMs;  // 10 Hz

struct Options {
  double seconds = 30.0;
  double work_ms = 30.0;   ///< optimizer CPU time per sweep
  int optimizer_nice = 0;  ///< added to the optimizer thread's nice value (≥ 0: no privilege)
  int fifo_priority = 0;   ///< > 0: SCHED_FIFO for the producer and propagator (CAP_SYS_NICE)
};

struct TimedSample {
  ImuSample sample;
  int64_t enqueue_ns = 0;  ///< CLOCK_MONOTONIC just before the push; < 0 ends the stream
};

int64_t ClockNs(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<int64_t>(ts.tv_sec) * kNsPerSec + ts.tv_nsec;
}
int64_t NowNs() { return ClockNs(CLOCK_MONOTONIC); }

void SleepUntil(int64_t t_ns) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(t_ns / kNsPerSec);
  ts.tv_nsec = static_cast<long>(t_ns % kNsPerSec);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) != 0) {
  }
}

// The level turn in closed form, t_s after the start (world origin, heading +x).
State TurnState(double t_s) {
  State s;
  const double yaw = kYawRateRadps * t_s, r = kSpeedMps / kYawRateRadps;
  s.T_world_imu.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  s.T_world_imu.translation() = Eigen::Vector3d(r * std::sin(yaw), r * (1.0 - std::cos(yaw)), 0.0);
  s.vel_world = kSpeedMps * Eigen::Vector3d(std::cos(yaw), std::sin(yaw), 0.0);
  return s;
}

ImuSample TurnSample(int64_t t_ns) {
  ImuSample s;
  s.t_ns = t_ns;
  s.gyro_radps = Eigen::Vector3d(0.0, 0.0, kYawRateRadps);
  s.acc_mps2 = Eigen::Vector3d(0.0, kSpeedMps * kYawRateRadps, kG);
  return s;
}

// ---- the optimizer's workload -------------------------------------------------------------

struct Workload {
  std::vector<Scan> scans;  ///< simulated `short` sweeps, seed 1, from 3 s
  std::vector<Eigen::Isometry3d> poses;
  VoxelMap plane_map{{.voxel_m = 0.5, .max_points_per_voxel = 10}};
  VoxelMap edge_map{{.voxel_m = 0.5, .max_points_per_voxel = 10}};
  FrontEnd front_end{FrontEndConfig{}};
  FrontEndOutput out;
  ScanMatcher matcher;
  std::vector<Eigen::Vector3d> planes, edges;
  size_t next = 0;

  void Features(const Scan& scan) {
    front_end.Process(scan, &out);
    planes.clear();
    edges.clear();
    for (const auto& f : out.features.planes) planes.push_back(f.xyz_m.cast<double>());
    for (const auto& f : out.features.edges) edges.push_back(f.xyz_m.cast<double>());
  }

  // One sweep's LiDAR-only work: front end, then registration from a guess 5 cm / 0.6° off.
  void OneSweep() {
    const size_t i = next++ % scans.size();
    Features(scans[i]);
    Eigen::Isometry3d guess = poses[i];
    guess.translate(Eigen::Vector3d(0.05, -0.03, 0.01));
    guess.rotate(Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitZ()));
    matcher.Match(planes, edges, plane_map, edge_map, guess);
  }
};

bool LoadWorkload(Workload* w) {
  auto setup = sim::MakeSimSetup("short", 1, 6.0);
  if (!setup) return false;
  sim::LabelledScanSource source(*setup);
  sim::LabelledScan ls;
  for (int i = 0; i < 20 && source.Next(&ls, 3.0 + 0.1 * i); ++i) {
    w->scans.push_back(ls.scan);
    w->poses.push_back(ls.T_world_lidar_end);
    w->Features(ls.scan);  // the map: every sweep's features at its true pose
    std::vector<Eigen::Vector3d> world;
    for (const auto& p : w->planes) world.push_back(ls.T_world_lidar_end * p);
    w->plane_map.Insert(world);
    world.clear();
    for (const auto& p : w->edges) world.push_back(ls.T_world_lidar_end * p);
    w->edge_map.Insert(world);
  }
  return !w->scans.empty();
}

// As the daemon would with swliod-realtime.conf: real-time priority for the rx and propagator
// threads only (they sleep almost all the time); the optimizer stays SCHED_OTHER.
void MaybeRealtime(int priority, const char* thread) {
  if (priority <= 0) return;
  sched_param param{};
  param.sched_priority = priority;
  const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
  if (err != 0) std::fprintf(stderr, "%s: SCHED_FIFO refused: %s\n", thread, std::strerror(err));
}

// ---- the three threads --------------------------------------------------------------------

using SampleQueue = moodycamel::BlockingReaderWriterQueue<TimedSample>;
using StateQueue = moodycamel::ReaderWriterQueue<State>;

struct Run {
  int64_t t0_ns = 0, end_ns = 0;
  SampleQueue samples{4096};  ///< producer: imu thread; consumer: propagator thread
  StateQueue states{64};      ///< producer: optimizer thread; consumer: propagator thread
  std::atomic<uint64_t> sample_drops{0}, state_drops{0};
  std::vector<int64_t> latency_ns, add_ns, set_state_ns, work_wall_ns;
  std::vector<int64_t> timer_late_ns;  ///< producer: wake-up − due time (OS/VM stalls)
  ImuRateCounters counters;
  ImuRateOutput last;
};

void Producer(Run* run, int fifo_priority) {
  MaybeRealtime(fifo_priority, "producer");
  for (int64_t t = run->t0_ns; t < run->end_ns; t += kImuPeriodNs) {
    SleepUntil(t);
    TimedSample ts{TurnSample(t), 0};
    ts.enqueue_ns = NowNs();
    run->timer_late_ns.push_back(ts.enqueue_ns - t);
    if (!run->samples.try_enqueue(ts)) ++run->sample_drops;
  }
  while (!run->samples.try_enqueue(TimedSample{ImuSample{}, -1})) SleepUntil(NowNs() + kNsPerMs);
}

void Optimizer(Run* run, Workload* work, const Options& options) {
  // Linux: the nice value is per thread (setpriority on the thread id).
  if (options.optimizer_nice != 0) {
    setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), options.optimizer_nice);
  }
  const auto budget_ns = static_cast<int64_t>(options.work_ms * 1e6);
  for (int64_t t = run->t0_ns + kSweepPeriodNs; t < run->end_ns; t += kSweepPeriodNs) {
    SleepUntil(t);
    const int64_t cpu0 = ClockNs(CLOCK_THREAD_CPUTIME_ID), wall0 = NowNs();
    while (ClockNs(CLOCK_THREAD_CPUTIME_ID) - cpu0 < budget_ns) work->OneSweep();
    run->work_wall_ns.push_back(NowNs() - wall0);
    State s = TurnState(NsToSec(t - run->t0_ns));  // "optimized" state at the sweep's end
    s.t_ns = t;
    s.T_world_imu.translation().x() += 0.01;  // a correction, so re-propagation changes things
    if (!run->states.try_enqueue(s)) ++run->state_drops;
    while (t + kSweepPeriodNs <= NowNs()) t += kSweepPeriodNs;  // skip sweeps that overran
  }
}

void Propagator(Run* run, int fifo_priority) {
  MaybeRealtime(fifo_priority, "propagator");
  ImuRatePropagator prop(ImuRatePropagatorConfig{.gravity_mps2 = kG, .buffer_samples = 800});
  State start = TurnState(0.0);
  start.t_ns = run->t0_ns;
  prop.SetState(start);
  TimedSample ts;
  for (;;) {
    if (!run->samples.wait_dequeue_timed(ts, 100'000)) continue;
    if (ts.enqueue_ns < 0) break;
    const int64_t before_ns = NowNs();
    const std::optional<ImuRateOutput> out = prop.Add(ts.sample);
    const int64_t output_ns = NowNs();  // where the publisher would be handed the output
    if (out) run->last = *out;
    run->latency_ns.push_back(output_ns - ts.enqueue_ns);
    run->add_ns.push_back(output_ns - before_ns);
    State s;
    while (run->states.try_dequeue(s)) {
      const int64_t t_ns = NowNs();
      if (const auto o = prop.SetState(s)) run->last = *o;
      run->set_state_ns.push_back(NowNs() - t_ns);
    }
  }
  run->counters = prop.counters();
}

// ---- report -------------------------------------------------------------------------------

double Percentile(std::vector<int64_t> v, double q) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<size_t>(q * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return static_cast<double>(v[k]);
}

void PrintStats(const char* what, const std::vector<int64_t>& v, double scale, const char* unit) {
  const double max = v.empty() ? 0.0 : static_cast<double>(*std::max_element(v.begin(), v.end()));
  std::printf("%-28s n=%-6zu p50 %8.1f  p99 %8.1f  p99.9 %8.1f  max %8.1f %s\n", what, v.size(),
              Percentile(v, 0.5) / scale, Percentile(v, 0.99) / scale, Percentile(v, 0.999) / scale,
              max / scale, unit);
}

void Report(const Run& run) {
  PrintStats("latency sample->output", run.latency_ns, 1e3, "us");
  PrintStats("  of which Add()", run.add_ns, 1e3, "us");
  PrintStats("SetState (re-propagation)", run.set_state_ns, 1e3, "us");
  PrintStats("producer timer lateness", run.timer_late_ns, 1e3, "us");
  PrintStats("optimizer work per sweep", run.work_wall_ns, 1e6, "ms wall");
  const ImuRateCounters& c = run.counters;
  std::printf(
      "samples %llu, out of order %llu, overflow %llu, states %llu, re-propagated %llu\n",
      static_cast<unsigned long long>(c.samples), static_cast<unsigned long long>(c.out_of_order),
      static_cast<unsigned long long>(c.overflow_dropped),
      static_cast<unsigned long long>(c.states), static_cast<unsigned long long>(c.repropagated));
  std::printf("queue drops: samples %llu, states %llu\n",
              static_cast<unsigned long long>(run.sample_drops.load()),
              static_cast<unsigned long long>(run.state_drops.load()));
  const State truth = TurnState(NsToSec(run.last.state.t_ns - run.t0_ns));
  std::printf("last output: %.3f s, %.1f ms since the optimized state, %.4f m from the turn\n",
              NsToSec(run.last.state.t_ns - run.t0_ns), NsToSec(run.last.since_optimized_ns) * 1e3,
              (run.last.state.T_world_imu.translation() - truth.T_world_imu.translation()).norm());
}

void PrintLoad(const char* when) {
  double load[3] = {0, 0, 0};
  if (getloadavg(load, 3) == 3) {
    std::printf("load average %s: %.2f %.2f %.2f\n", when, load[0], load[1], load[2]);
  }
}

Options ParseOptions(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    const double value = std::strtod(argv[i + 1], nullptr);
    if (key == "--seconds") o.seconds = value;
    if (key == "--work-ms") o.work_ms = value;
    if (key == "--optimizer-nice") o.optimizer_nice = static_cast<int>(value);
    if (key == "--fifo") o.fifo_priority = static_cast<int>(value);
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = ParseOptions(argc, argv);
  Workload work;
  if (!LoadWorkload(&work)) return 1;
  Run run;
  const auto n = static_cast<size_t>(options.seconds * 400.0 * 1.1) + 16;
  run.latency_ns.reserve(n);
  run.add_ns.reserve(n);
  run.timer_late_ns.reserve(n);
  run.set_state_ns.reserve(n / 40);
  run.work_wall_ns.reserve(n / 40);
  std::printf(
      "%zu simulated sweeps; %.0f s at 400 Hz, optimizer %.1f ms CPU per 100 ms, nice +%d\n",
      work.scans.size(), options.seconds, options.work_ms, options.optimizer_nice);
  PrintLoad("before");
  run.t0_ns = NowNs() + 50 * kNsPerMs;
  run.end_ns = run.t0_ns + SecToNs(options.seconds);
  std::thread propagator(Propagator, &run, options.fifo_priority);
  std::thread optimizer(Optimizer, &run, &work, std::cref(options));
  std::thread producer(Producer, &run, options.fifo_priority);
  producer.join();
  optimizer.join();
  propagator.join();
  PrintLoad("after");
  Report(run);
  return 0;
}
