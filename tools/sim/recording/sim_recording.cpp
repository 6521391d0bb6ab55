#include "recording/sim_recording.h"

#include <cinttypes>
#include <cstdio>
#include <fstream>
#include <memory>
#include <vector>

#include "recording/actors_csv.h"
#include "swlio/core/exact_number.h"
#include "swlio/core/lie.h"
#include "swlio/core/time.h"
#include "swlio/drivers/pcap_file.h"
#include "swlio/drivers/xsens/mtdata2.h"
#include "swlio/drivers/xsens/xbus.h"

namespace swlio::sim {
namespace {

namespace xs = drivers::xsens;

std::string Format(const char* fmt, auto... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, fmt, args...);
  return buf;
}

bool WriteGroundTruth(const SimSetup& setup,
                      const std::filesystem::path& path,
                      RecordingStats* stats) {
  std::ofstream out(path);
  out << "# timestamp tx ty tz qx qy qz qw  (IMU body frame in the world frame, host time s)\n";
  const double dt = 1.0 / setup.gt_rate_hz;
  const double duration = SimDuration(setup);
  for (int64_t k = 0; static_cast<double>(k) * dt <= duration; ++k) {
    const double t = static_cast<double>(k) * dt;
    out << TumLine(setup, t, kFileHostStartNs + SecToNs(t)) << '\n';
    ++stats->gt_poses;
  }
  return static_cast<bool>(out);
}

bool WriteImu(const SimSetup& setup, const std::filesystem::path& dir, RecordingStats* stats) {
  const std::vector<SimImuSample> samples = SimulateImu(*setup.trajectory, setup.imu, setup.seed);
  const std::vector<SimGnssFix> fixes =
      SimulateGnss(*setup.trajectory, setup.gnss, samples, setup.seed);
  size_t next_fix = 0;
  std::ofstream bytes(dir / "imu.xbus", std::ios::binary);
  std::ofstream rx(dir / "imu.rx.csv");
  rx << "byte_offset,bytes,t_rx_ns\n";
  std::array<uint8_t, xs::kXbusMaxFrame> frame{};
  uint64_t offset = 0;
  size_t i = 0;
  while (i < samples.size()) {  // one burst: every frame with the same receive time
    const int64_t t_rx = samples[i].t_rx_ns;
    const uint64_t burst_start = offset;
    for (; i < samples.size() && samples[i].t_rx_ns == t_rx; ++i) {
      const size_t n = EncodeImuFrame(samples[i], frame, PvtForSample(fixes, i, &next_fix));
      bytes.write(reinterpret_cast<const char*>(frame.data()), static_cast<std::streamsize>(n));
      offset += n;
      ++stats->imu_frames;
    }
    rx << burst_start << ',' << (offset - burst_start) << ',' << (t_rx + kFileHostStartNs) << '\n';
  }
  for (const SimGnssFix& f : fixes) stats->gnss_no_fix += f.has_fix ? 0 : 1;
  stats->gnss_items = fixes.size();
  return static_cast<bool>(bytes) && static_cast<bool>(rx);
}

bool WriteWheels(const SimSetup& setup, const std::filesystem::path& dir, RecordingStats* stats) {
  if (!setup.wheel.enabled) return true;
  const std::vector<SimWheelSample> wheels =
      SimulateWheels(*setup.trajectory, setup.wheel, setup.seed);
  std::ofstream can_log(dir / "can.log");
  std::ofstream truth(dir / "wheel_truth.csv");
  stats->wheel_frames = wheels.size();
  return WriteCanLog(wheels, kFileHostStartNs, can_log) &&
         WriteWheelTruth(wheels, kFileHostStartNs, truth);
}

bool WriteLidar(const SimSetup& setup,
                const std::filesystem::path& path,
                RecordingStats* stats,
                std::string* error) {
  auto writer = drivers::PcapWriter::Create(path.string(), {}, error);
  if (!writer) return false;
  LidarSimulator lidar(setup.world.get(), setup.trajectory.get(), setup.lidar, setup.seed);
  SimPacket packet;
  std::vector<SimReturn> returns;
  while (lidar.Next(&packet, &returns)) {
    const bool msop = packet.dst_port == setup.lidar.msop_port;
    if (msop) {
      for (const SimReturn& r : returns) stats->valid_returns += r.range_m > 0.0 ? 1 : 0;
    }
    if (!writer->Write(packet.t_rx_ns + kFileHostStartNs, packet.dst_port, packet.dst_port,
                       packet.bytes)) {
      *error = "cannot write " + path.string();
      return false;
    }
  }
  stats->msop_packets = lidar.msop_packets();
  stats->difop_packets = lidar.difop_packets();
  return writer->Flush();
}

}  // namespace

size_t EncodeImuFrame(const SimImuSample& sample,
                      std::span<uint8_t> out,
                      const xs::XsensGnssPvt* gnss_pvt) {
  xs::MtData2Sample m;
  if (gnss_pvt != nullptr) m.gnss_pvt = *gnss_pvt;
  m.packet_counter = sample.packet_counter;
  m.sample_time_fine = sample.sample_time_fine;
  const double acc[3] = {sample.acc_mps2.x(), sample.acc_mps2.y(), sample.acc_mps2.z()};
  const double gyro[3] = {sample.gyro_radps.x(), sample.gyro_radps.y(), sample.gyro_radps.z()};
  m.acc_mps2 = xs::MakeXsensReal(acc);
  m.rate_of_turn_radps = xs::MakeXsensReal(gyro);
  std::array<uint8_t, 256> payload{};
  const size_t n = xs::EncodeMtData2(m, payload);
  if (n == 0) return 0;
  return xs::EncodeXbusFrame(xs::mid::kMtData2, std::span(payload).first(n), out);
}

const xs::XsensGnssPvt* PvtForSample(const std::vector<SimGnssFix>& fixes,
                                     size_t index,
                                     size_t* next) {
  while (*next < fixes.size() && fixes[*next].imu_index < index) ++*next;
  if (*next < fixes.size() && fixes[*next].imu_index == index) return &fixes[(*next)++].pvt;
  return nullptr;
}

std::string TumLine(const SimSetup& setup, double t_s, int64_t host_ns) {
  const Kinematics k = setup.trajectory->At(t_s);
  const Eigen::Quaterniond q = lie::PositiveW(Eigen::Quaterniond(k.R_world_body));
  const int64_t t_ns = host_ns;
  std::string line = Format("%" PRId64 ".%09" PRId64, t_ns / kNsPerSec, t_ns % kNsPerSec);
  for (const double v : {k.p_world.x(), k.p_world.y(), k.p_world.z(), q.x(), q.y(), q.z(), q.w()}) {
    line += ' ' + ExactNumber(v);  // the truth to the last bit: other programs read it
  }
  return line;
}

bool WriteRecording(const SimSetup& setup,
                    const std::filesystem::path& dir,
                    RecordingStats* stats,
                    std::string* error) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    *error = "cannot create " + dir.string() + ": " + ec.message();
    return false;
  }
  *stats = RecordingStats{};
  if (!WriteLidar(setup, dir / "lidar.pcap", stats, error)) return false;
  if (!WriteImu(setup, dir, stats)) {
    *error = "cannot write the IMU files in " + dir.string();
    return false;
  }
  if (!WriteWheels(setup, dir, stats)) {
    *error = "cannot write can.log / wheel_truth.csv in " + dir.string();
    return false;
  }
  if (!WriteGroundTruth(setup, dir / "groundtruth.tum", stats)) {
    *error = "cannot write groundtruth.tum";
    return false;
  }
  if (setup.world->actors) {
    std::ofstream actors(dir / "actors.csv");
    if (!WriteActorsCsv(
            *setup.world->actors, SimDuration(setup),
            [](double t_s) { return kFileHostStartNs + SecToNs(t_s); }, actors)) {
      *error = "cannot write actors.csv";
      return false;
    }
  }
  std::ofstream manifest(dir / "manifest.yaml");
  manifest << ManifestYaml(setup, *stats, kFileHostStartNs, "file");
  if (!manifest) {
    *error = "cannot write manifest.yaml";
    return false;
  }
  return true;
}

}  // namespace swlio::sim
