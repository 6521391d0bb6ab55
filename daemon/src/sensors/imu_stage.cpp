#include "swlio/daemon/sensors/imu_stage.h"

namespace swlio::daemon {
namespace {

drivers::ClockModelConfig XsensClockConfig() {
  drivers::ClockModelConfig c;
  c.wrap_period_ns = drivers::xsens::SampleTimeFineToNs(0xFFFFFFFFu) + 100'000;
  // Serial bytes reach the reader through the kernel's tty flip buffer, which a kernel worker
  // empties; on a busy host that worker was measured waiting up to 5 s to run, and a real
  // adapter's buffer holds 640 KiB, about 27 s of MTi data at 400 Hz, before it drops a byte
  // (tools/sim/live/serial_backlog.h). Samples up to that late are a backlog, not the device's
  // clock stepping back (SampleTimeFine is a free-running counter; a device reset sets it back
  // by far more).
  c.backlog_ns = 30'000'000'000;
  return c;
}

}  // namespace

ImuRaw ToImuRaw(const drivers::xsens::MtData2Sample& sample, int64_t t_rx_ns, size_t frame_bytes) {
  ImuRaw raw;
  raw.t_rx_ns = t_rx_ns;
  raw.frame_bytes = static_cast<uint32_t>(frame_bytes);
  raw.has_sample_time_fine = sample.sample_time_fine.has_value();
  raw.sample_time_fine = sample.sample_time_fine.value_or(0);
  if (const std::optional<ImuSample> s = drivers::xsens::ToImuSample(sample, t_rx_ns)) {
    raw.has_inertial = true;
    raw.acc_mps2 = s->acc_mps2;
    raw.gyro_radps = s->gyro_radps;
  }
  if (sample.gnss_pvt) {
    raw.has_gnss_pvt = true;
    raw.gnss_pvt = *sample.gnss_pvt;
  }
  return raw;
}

ImuStage::ImuStage(int64_t baud)
    : baud_(baud), clock_config_(XsensClockConfig()), clock_(clock_config_) {}

std::optional<ImuSample> ImuStage::Map(const ImuRaw& raw) {
  if (!raw.has_sample_time_fine) {
    ++counters_.no_sample_time;
    return std::nullopt;
  }
  // Transmission time of the frame: 10 bits per byte on an 8N1 line.
  const int64_t tx_ns = baud_ > 0 ? static_cast<int64_t>(static_cast<double>(raw.frame_bytes) *
                                                         10.0 / static_cast<double>(baud_) * 1e9)
                                  : 0;
  if (!latency_set_) {
    clock_config_.fixed_latency_ns = tx_ns;
    clock_ = drivers::ClockModel(clock_config_);
    latency_set_ = true;
  }
  // Frames differ in length (a GnssPvtData item adds 97 bytes, ~1 ms at 921600 baud): each
  // one's receive time is moved to where a frame of the first one's length would have ended,
  // so the model's fixed latency holds for all.
  const int64_t t_rx_ns = raw.t_rx_ns - (tx_ns - clock_config_.fixed_latency_ns);
  const int64_t stf_ns = drivers::xsens::SampleTimeFineToNs(raw.sample_time_fine);
  const int64_t t_host_ns = clock_.Observe(stf_ns, t_rx_ns);
  if (!raw.has_inertial || !raw.acc_mps2.allFinite() || !raw.gyro_radps.allFinite()) {
    ++counters_.incomplete;
    return std::nullopt;
  }
  if (counters_.samples > 0 && t_host_ns <= last_t_ns_) {
    ++counters_.out_of_order;
    return std::nullopt;
  }
  ImuSample out;
  out.t_ns = t_host_ns;
  out.acc_mps2 = raw.acc_mps2;
  out.gyro_radps = raw.gyro_radps;
  last_t_ns_ = t_host_ns;
  ++counters_.samples;
  return out;
}

}  // namespace swlio::daemon
