// IMU-rate output latency while the real window estimator runs (issue 6: p99 ≤ 1 ms from IMU
// sample to output). Not a Google Benchmark: a real-time program with its own main (which takes
// precedence over the one in libbenchmark_main.a). It replays a recording folder (--recording
// DIR, e.g. from `swlio-sim --scenario short --seed 1 --out DIR`; without it the `short` drive,
// seed 1, is simulated into a temporary folder first) in real time with three threads as in
// design.md:
//   imu producer  – at each IMU sample's recorded time (clock_nanosleep on CLOCK_MONOTONIC, the
//                   clock of std::chrono::steady_clock, absolute) stamps it and pushes it into a
//                   bounded SPSC queue (moodycamel BlockingReaderWriterQueue);
//   propagator    – blocks on that queue, runs ImuRatePropagator::Add and takes the output time
//                   at once (latency = output time − the sample's push time); between samples
//                   it takes the newest optimized state from a second SPSC queue (lock-free:
//                   the optimizer never blocks it) and re-propagates (SetState);
//   optimizer     – WindowEstimator over the recording's sweeps, each released at its real time
//                   (once the first IMU sample after the sweep's end is due, as swlio-run waits
//                   for it), fed the same IMU samples from its own RecordingReader; each
//                   tracked sweep's state (pose, velocity, biases, sweep end time) is pushed.
// Sanity (so the bench cannot look good by doing nothing): at each handoff, the propagated
// output at the optimized state's time (interpolated between the two outputs around it) against
// that state; after the run, every output and every optimized state against the recording's
// ground truth (aligned at the first optimized state).
// By default nothing is pinned and no real-time priority is asked for: the figure is what a plain
// SCHED_OTHER process gets on the machine as it is (its load average is printed). --fifo P gives
// the producer and propagator threads SCHED_FIFO priority P, as systemd/swliod-realtime.conf
// allows the daemon.
//
//   swlio_imu_rate_latency_bench [--recording DIR] [--seconds 0 (whole drive)]
//                                [--optimizer-nice 0] [--fifo 0]

#include <pthread.h>
#include <readerwriterqueue.h>
#include <sched.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "recording_replay.h"
#include "swlio/core/time.h"
#include "swlio/estimator/imu/imu_rate_propagator.h"
#include "swlio/estimator/window/window_estimator.h"

namespace {

using namespace swlio;             // NOLINT(google-build-using-namespace): bench file only
using namespace swlio::estimator;  // NOLINT(google-build-using-namespace)

struct Options {
  std::string recording;   ///< empty: simulate `short`, seed 1, into a temporary folder
  double seconds = 0.0;    ///< replay this much of the recording; 0: all of it
  int optimizer_nice = 0;  ///< added to the optimizer thread's nice value (≥ 0: no privilege)
  int fifo_priority = 0;   ///< > 0: SCHED_FIFO for the producer and propagator (CAP_SYS_NICE)
};

struct TimedSample {
  ImuSample sample;
  int64_t enqueue_ns = 0;  ///< CLOCK_MONOTONIC just before the push; < 0 ends the stream
};

struct TimedPosition {
  int64_t t_ns = 0;
  Eigen::Vector3d p_world = Eigen::Vector3d::Zero();
};

int64_t ClockNs(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<int64_t>(ts.tv_sec) * kNsPerSec + ts.tv_nsec;
}
int64_t NowNs() { return ClockNs(CLOCK_MONOTONIC); }
int64_t ThreadCpuNs() { return ClockNs(CLOCK_THREAD_CPUTIME_ID); }

void SleepUntil(int64_t t_ns) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(t_ns / kNsPerSec);
  ts.tv_nsec = static_cast<long>(t_ns % kNsPerSec);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) != 0) {
  }
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
  int64_t wall0_ns = 0;       ///< CLOCK_MONOTONIC at which the recording's rec0_ns is replayed
  int64_t rec0_ns = 0;        ///< first IMU sample (recording host time)
  int64_t rec_end_ns = 0;     ///< nothing later is replayed
  SampleQueue samples{4096};  ///< producer: imu thread; consumer: propagator thread
  StateQueue states{64};      ///< producer: optimizer thread; consumer: propagator thread
  std::atomic<uint64_t> sample_drops{0}, state_drops{0};
  // Written by the producer.
  std::vector<int64_t> timer_late_ns;  ///< wake-up − due time (OS/VM stalls)
  // Written by the propagator (reserved before the run: no allocation in its loop).
  std::vector<int64_t> latency_ns, add_ns, set_state_ns, since_optimized_ns;
  std::vector<int64_t> handoff_jump_um;  ///< |output − optimized state| at the state's time
  std::vector<TimedPosition> outputs;
  uint64_t without_output = 0;  ///< samples before the first optimized state
  uint64_t superseded = 0;      ///< states replaced by a newer one before being applied
  ImuRateCounters counters;
  // Written by the optimizer.
  std::vector<int64_t> sweep_wall_ns, sweep_cpu_ns, state_age_ns;
  std::vector<State> optimized;
  size_t sweeps = 0, untracked = 0;

  int64_t Wall(int64_t t_rec_ns) const { return wall0_ns + (t_rec_ns - rec0_ns); }
};

void Producer(Run* run, const std::vector<ImuSample>* imu, int fifo_priority) {
  MaybeRealtime(fifo_priority, "producer");
  for (const ImuSample& sample : *imu) {
    if (sample.t_ns > run->rec_end_ns) break;
    const int64_t due_ns = run->Wall(sample.t_ns);
    SleepUntil(due_ns);
    TimedSample ts{sample, 0};
    ts.enqueue_ns = NowNs();
    run->timer_late_ns.push_back(ts.enqueue_ns - due_ns);
    if (!run->samples.try_enqueue(ts)) ++run->sample_drops;
  }
  while (!run->samples.try_enqueue(TimedSample{ImuSample{}, -1})) SleepUntil(NowNs() + kNsPerMs);
}

void OptimizeSweep(Run* run, WindowEstimator* window, const Scan& scan) {
  const int64_t wall0_ns = NowNs(), cpu0_ns = ThreadCpuNs();
  const WindowResult r = window->AddScan(scan);
  const int64_t done_ns = NowNs();
  run->sweep_wall_ns.push_back(done_ns - wall0_ns);
  run->sweep_cpu_ns.push_back(ThreadCpuNs() - cpu0_ns);
  ++run->sweeps;
  const OdometryStatus status = r.odometry.status;
  if (status != OdometryStatus::kTracking && status != OdometryStatus::kMatchFailed) {
    ++run->untracked;
    return;
  }
  run->state_age_ns.push_back(done_ns - run->Wall(r.odometry.state.t_ns));
  run->optimized.push_back(r.odometry.state);
  if (!run->states.try_enqueue(r.odometry.state)) ++run->state_drops;
}

void Optimizer(Run* run,
               daemon::RecordingReader* reader,
               const WindowEstimatorConfig* config,
               int nice) {
  // Linux: the nice value is per thread (setpriority on the thread id).
  if (nice != 0) setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), nice);
  WindowEstimator window(*config, &ThreadCpuNs);
  std::deque<Scan> waiting;
  daemon::RecordingEvent e;
  while (reader->Next(&e)) {
    if (e.kind == daemon::RecordingEvent::Kind::kScan) {
      if (e.scan.t_end_ns < run->rec_end_ns) waiting.push_back(std::move(e.scan));
      continue;
    }
    if (e.imu.t_ns > run->rec_end_ns) break;
    // A sweep is processed once an IMU sample after its end exists: wait for that sample's time.
    const bool release = !waiting.empty() && waiting.front().t_end_ns < e.imu.t_ns;
    if (release) SleepUntil(run->Wall(e.imu.t_ns));
    window.AddImu(e.imu);
    while (!waiting.empty() && waiting.front().t_end_ns < e.imu.t_ns) {
      OptimizeSweep(run, &window, waiting.front());
      waiting.pop_front();
    }
  }
}

// The output at `t_ns` interpolated between the two recent outputs around it.
std::optional<Eigen::Vector3d> RecentAt(const std::array<TimedPosition, 256>& recent,
                                        size_t count,
                                        int64_t t_ns) {
  const size_t n = std::min(count, recent.size());
  for (size_t k = 1; k < n; ++k) {
    const TimedPosition& a = recent[(count - n + k - 1) % recent.size()];
    const TimedPosition& b = recent[(count - n + k) % recent.size()];
    if (a.t_ns <= t_ns && t_ns <= b.t_ns && b.t_ns > a.t_ns) {
      const double w = static_cast<double>(t_ns - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns);
      return (1.0 - w) * a.p_world + w * b.p_world;
    }
  }
  return std::nullopt;
}

// Applies the newest waiting optimized state, if any (never waits).
void TakeState(Run* run,
               ImuRatePropagator* prop,
               const std::array<TimedPosition, 256>& recent,
               size_t count) {
  State s, newest;
  bool any = false;
  while (run->states.try_dequeue(s)) {
    run->superseded += any ? 1 : 0;
    newest = s;
    any = true;
  }
  if (!any) return;
  if (const auto p = RecentAt(recent, count, newest.t_ns)) {
    const double jump_m = (*p - newest.T_world_imu.translation()).norm();
    run->handoff_jump_um.push_back(static_cast<int64_t>(jump_m * 1e6));
  }
  const int64_t t_ns = NowNs();
  prop->SetState(newest);
  run->set_state_ns.push_back(NowNs() - t_ns);
}

void Propagator(Run* run, double gravity_mps2, int fifo_priority) {
  MaybeRealtime(fifo_priority, "propagator");
  ImuRatePropagator prop(
      ImuRatePropagatorConfig{.gravity_mps2 = gravity_mps2, .buffer_samples = 800});
  std::array<TimedPosition, 256> recent{};  ///< the last outputs, for the handoff check
  size_t count = 0;
  TimedSample ts;
  for (;;) {
    if (!run->samples.wait_dequeue_timed(ts, 10'000)) {  // µs
      TakeState(run, &prop, recent, count);
      continue;
    }
    if (ts.enqueue_ns < 0) break;
    const int64_t before_ns = NowNs();
    const std::optional<ImuRateOutput> out = prop.Add(ts.sample);
    const int64_t output_ns = NowNs();  // where the publisher would be handed the output
    if (out) {
      run->latency_ns.push_back(output_ns - ts.enqueue_ns);
      run->add_ns.push_back(output_ns - before_ns);
      run->since_optimized_ns.push_back(out->since_optimized_ns);
      const TimedPosition tp{out->state.t_ns, out->state.T_world_imu.translation()};
      run->outputs.push_back(tp);
      recent[count++ % recent.size()] = tp;
    } else {
      ++run->without_output;
    }
    TakeState(run, &prop, recent, count);
  }
  run->counters = prop.counters();
}

// ---- report -------------------------------------------------------------------------------

template <typename T>
double Percentile(std::vector<T> v, double q) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<size_t>(q * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return static_cast<double>(v[k]);
}

template <typename T>
void PrintStats(const char* what, const std::vector<T>& v, double scale, const char* unit) {
  const double max = v.empty() ? 0.0 : static_cast<double>(*std::max_element(v.begin(), v.end()));
  std::printf("%-30s n=%-6zu p50 %8.2f  p90 %8.2f  p99 %8.2f  p99.9 %8.2f  max %8.2f %s\n", what,
              v.size(), Percentile(v, 0.5) / scale, Percentile(v, 0.9) / scale,
              Percentile(v, 0.99) / scale, Percentile(v, 0.999) / scale, max / scale, unit);
}

// Position errors against the ground truth, both trajectories aligned at the first optimized
// state (the estimator's world is its own: gravity-aligned, origin at its start).
void ReportTruth(const Run& run, const bench::Truth& truth) {
  if (run.optimized.empty()) return;
  const auto T_gt0 = truth.At(run.optimized.front().t_ns);
  if (!T_gt0) return;
  const Eigen::Isometry3d T_gt_est = *T_gt0 * run.optimized.front().T_world_imu.inverse();
  std::vector<double> out_err_m, opt_err_m;
  for (const TimedPosition& o : run.outputs) {
    if (const auto T = truth.At(o.t_ns))
      out_err_m.push_back((T_gt_est * o.p_world - T->translation()).norm());
  }
  for (const State& s : run.optimized) {
    if (const auto T = truth.At(s.t_ns)) {
      opt_err_m.push_back((T_gt_est * s.T_world_imu.translation() - T->translation()).norm());
    }
  }
  PrintStats("vs truth: IMU-rate outputs", out_err_m, 1.0, "m");
  PrintStats("vs truth: optimized states", opt_err_m, 1.0, "m");
}

void Report(const Run& run, size_t imu_total) {
  const ImuRateCounters& c = run.counters;
  std::printf("samples pushed %zu (of %zu), with output %zu, before the first state %llu\n",
              run.timer_late_ns.size(), imu_total, run.latency_ns.size(),
              static_cast<unsigned long long>(run.without_output));
  PrintStats("latency sample->output", run.latency_ns, 1e3, "us");
  PrintStats("  of which Add()", run.add_ns, 1e3, "us");
  PrintStats("SetState (re-propagation)", run.set_state_ns, 1e3, "us");
  PrintStats("producer timer lateness", run.timer_late_ns, 1e3, "us");
  PrintStats("output since optimized state", run.since_optimized_ns, 1e6, "ms");
  PrintStats("optimizer per sweep, wall", run.sweep_wall_ns, 1e6, "ms");
  PrintStats("optimizer per sweep, CPU", run.sweep_cpu_ns, 1e6, "ms");
  PrintStats("state age at handoff", run.state_age_ns, 1e6, "ms");
  PrintStats("output vs state at handoff", run.handoff_jump_um, 1e3, "mm");
  std::printf(
      "sweeps %zu, not tracking %zu; propagator: samples %llu, out of order %llu, overflow %llu, "
      "states %llu (superseded %llu), re-propagated %llu\n",
      run.sweeps, run.untracked, static_cast<unsigned long long>(c.samples),
      static_cast<unsigned long long>(c.out_of_order),
      static_cast<unsigned long long>(c.overflow_dropped),
      static_cast<unsigned long long>(c.states), static_cast<unsigned long long>(run.superseded),
      static_cast<unsigned long long>(c.repropagated));
  std::printf("queue drops: samples %llu, states %llu\n",
              static_cast<unsigned long long>(run.sample_drops.load()),
              static_cast<unsigned long long>(run.state_drops.load()));
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
    if (key == "--recording") o.recording = argv[i + 1];
    if (key == "--seconds") o.seconds = value;
    if (key == "--optimizer-nice") o.optimizer_nice = static_cast<int>(value);
    if (key == "--fifo") o.fifo_priority = static_cast<int>(value);
  }
  return o;
}

// Loads everything the run needs; false (after a message) on failure.
struct Setup {
  std::filesystem::path dir;
  bool temporary = false;
  daemon::DaemonConfig daemon;
  WindowEstimatorConfig window;
  std::vector<ImuSample> imu;
  bench::Truth truth;
  std::unique_ptr<daemon::RecordingReader> reader;  ///< the optimizer's
};

bool Load(const Options& options, Setup* s) {
  std::string error;
  s->dir = options.recording;
  if (s->dir.empty()) {
    const int64_t t0_ns = NowNs();
    s->dir = bench::WriteShortDrive(&error);
    if (s->dir.empty()) {
      std::fprintf(stderr, "simulating `short`: %s\n", error.c_str());
      return false;
    }
    s->temporary = true;
    std::printf("simulated `short`, seed 1, into %s in %.1f s\n", s->dir.c_str(),
                NsToSec(NowNs() - t0_ns));
  }
  s->window.odometry.estimator = s->daemon.estimator;
  s->window.odometry.T_imu_lidar = daemon::ManifestExtrinsic(s->dir).value_or(
      s->daemon.estimator.extrinsic_imu_lidar.ToIsometry());
  if (!bench::ReadImu(s->dir, s->daemon, &s->imu, &error)) {
    std::fprintf(stderr, "%s: no IMU samples %s\n", s->dir.c_str(), error.c_str());
    return false;
  }
  if (!s->truth.Load(s->dir / "groundtruth.tum")) std::printf("no ground truth in the recording\n");
  s->reader = daemon::RecordingReader::Open(s->dir, s->daemon.lidar, s->daemon.imu, &error);
  if (!s->reader) std::fprintf(stderr, "%s\n", error.c_str());
  return s->reader != nullptr;
}

void Reserve(Run* run, size_t n) {
  for (auto* v : {&run->timer_late_ns, &run->latency_ns, &run->add_ns, &run->since_optimized_ns}) {
    v->reserve(n);
  }
  run->outputs.reserve(n);
  for (auto* v : {&run->set_state_ns, &run->handoff_jump_um, &run->sweep_wall_ns,
                  &run->sweep_cpu_ns, &run->state_age_ns}) {
    v->reserve(n / 20);
  }
  run->optimized.reserve(n / 20);
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = ParseOptions(argc, argv);
  Setup setup;
  if (!Load(options, &setup)) return 1;
  Run run;
  run.rec0_ns = setup.imu.front().t_ns;
  run.rec_end_ns =
      options.seconds > 0.0 ? run.rec0_ns + SecToNs(options.seconds) : setup.imu.back().t_ns;
  Reserve(&run, setup.imu.size() + 16);
  std::printf("%s: %zu IMU samples, replaying %.1f s; optimizer nice +%d, fifo %d\n",
              setup.dir.c_str(), setup.imu.size(), NsToSec(run.rec_end_ns - run.rec0_ns),
              options.optimizer_nice, options.fifo_priority);
  PrintLoad("before");
  run.wall0_ns = NowNs() + 50 * kNsPerMs;
  std::thread propagator(Propagator, &run, setup.daemon.estimator.gravity_mps2,
                         options.fifo_priority);
  std::thread optimizer(Optimizer, &run, setup.reader.get(), &setup.window, options.optimizer_nice);
  std::thread producer(Producer, &run, &setup.imu, options.fifo_priority);
  producer.join();
  optimizer.join();
  propagator.join();
  PrintLoad("after");
  Report(run, setup.imu.size());
  ReportTruth(run, setup.truth);
  if (setup.temporary) std::filesystem::remove_all(setup.dir);
  return 0;
}
