// swlio-decode xsens FILE.bin [--summary] [--csv OUT.csv]
//
// Runs a raw Xbus byte log (what the MTi sent on its serial port) through the resynchronizing
// framer and the MTData2 decoder. --summary prints one JSON object of counters; --csv writes
// one line per MTData2 message with every decoded value (empty cells for absent items).

#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "decode_command.h"
#include "swlio/drivers/xsens/mtdata2.h"
#include "swlio/drivers/xsens/xbus.h"

namespace swlio::tools {
namespace {

namespace xs = drivers::xsens;

struct XsensArgs {
  std::string file;
  bool summary = false;
  std::string csv;
};

struct XsensTotals {
  uint64_t bytes = 0;
  std::map<uint8_t, uint64_t> frames_by_mid;
  std::map<uint16_t, uint64_t> items_by_xdi;
  uint64_t samples = 0, truncated = 0, unknown_items = 0, bad_size_items = 0, imu_samples = 0;
  uint64_t counter_gaps = 0, missing_packets = 0;
  std::optional<uint16_t> first_counter, last_counter;
};

std::string Hex(unsigned v, int digits) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "\"0x%0*X\"", digits, v);
  return buf;
}

std::string JsonString(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// ---- CSV ----------------------------------------------------------------------------------

constexpr const char* kCsvHeader =
    "frame,packet_counter,sample_time_fine,sample_time_coarse,utc,status,"
    "acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z,quat_w,quat_x,quat_y,quat_z,"
    "euler_roll_deg,euler_pitch_deg,euler_yaw_deg,free_acc_x,free_acc_y,free_acc_z,"
    "dv_x,dv_y,dv_z,dq_w,dq_x,dq_y,dq_z,mag_x,mag_y,mag_z,temperature_degc,baro_pa,"
    "lat_deg,lon_deg,alt_ellipsoid_m,vel_x,vel_y,vel_z";

// Every cell after the first is written as ",value" so rows need no trimming.
void CsvInt(std::FILE* f, const auto& opt) {
  std::fputc(',', f);
  if (opt) std::fprintf(f, "%llu", static_cast<unsigned long long>(*opt));
}

void CsvReal(std::FILE* f, const std::optional<xs::XsensReal>& r, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    std::fputc(',', f);
    if (r && i < r->count) std::fprintf(f, "%.17g", r->v[i]);
  }
}

void CsvRow(std::FILE* f, uint64_t frame, const xs::MtData2Sample& s) {
  std::fprintf(f, "%llu", static_cast<unsigned long long>(frame));
  CsvInt(f, s.packet_counter);
  CsvInt(f, s.sample_time_fine);
  CsvInt(f, s.sample_time_coarse);
  std::fputc(',', f);
  if (s.utc_time) {
    const auto& t = *s.utc_time;
    std::fprintf(f, "%04u-%02u-%02uT%02u:%02u:%02u.%09uZ", t.year, t.month, t.day, t.hour, t.minute,
                 t.second, t.nanoseconds);
  }
  std::fputc(',', f);
  if (s.status_word) {
    std::fprintf(f, "0x%08X", *s.status_word);
  } else if (s.status_byte) {
    std::fprintf(f, "0x%02X", *s.status_byte);
  }
  CsvReal(f, s.acc_mps2 ? s.acc_mps2 : s.acc_hr_mps2, 3);
  CsvReal(f, s.rate_of_turn_radps ? s.rate_of_turn_radps : s.rate_of_turn_hr_radps, 3);
  CsvReal(f, s.quaternion, 4);
  CsvReal(f, s.euler_deg, 3);
  CsvReal(f, s.free_acc_mps2, 3);
  CsvReal(f, s.delta_v_mps, 3);
  CsvReal(f, s.delta_q, 4);
  CsvReal(f, s.mag_au, 3);
  CsvReal(f, s.temperature_degc, 1);
  CsvInt(f, s.baro_pressure_pa);
  CsvReal(f, s.lat_lon_deg, 2);
  CsvReal(f, s.altitude_ellipsoid_m, 1);
  CsvReal(f, s.velocity_mps, 3);
  std::fputc('\n', f);
}

// ---- decoding -----------------------------------------------------------------------------

void Account(const xs::MtData2Sample& s, XsensTotals* t) {
  ++t->samples;
  t->unknown_items += s.unknown_items;
  t->bad_size_items += s.bad_size_items;
  for (size_t i = 0; i < s.item_count; ++i) ++t->items_by_xdi[s.item_ids[i]];
  if (xs::ToImuSample(s, 0)) ++t->imu_samples;
  if (!s.packet_counter) return;
  const uint16_t c = *s.packet_counter;
  if (t->last_counter) {
    const auto step = static_cast<uint16_t>(c - *t->last_counter);
    if (step != 1) ++t->counter_gaps;
    // Forward jumps count as losses; repeats and backward jumps (device reset) do not.
    if (step > 1 && step < 0x8000) t->missing_packets += step - 1u;
  }
  if (!t->first_counter) t->first_counter = c;
  t->last_counter = c;
}

bool Decode(const XsensArgs& args, XsensTotals* totals, xs::XbusFramerStats* stats) {
  std::ifstream in(args.file, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "cannot open %s\n", args.file.c_str());
    return false;
  }
  std::FILE* csv = nullptr;
  if (!args.csv.empty()) {
    csv = std::fopen(args.csv.c_str(), "w");
    if (csv == nullptr) {
      std::fprintf(stderr, "cannot write %s\n", args.csv.c_str());
      return false;
    }
    std::fprintf(csv, "%s\n", kCsvHeader);
  }
  auto framer = std::make_unique<xs::XbusFramer>();
  std::vector<char> chunk(1 << 16);
  xs::MtData2Sample sample;
  xs::XbusFrame frame;
  while (in.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || in.gcount() > 0) {
    const auto* data = reinterpret_cast<const uint8_t*>(chunk.data());
    size_t pos = 0;
    const auto n = static_cast<size_t>(in.gcount());
    while (pos < n) {
      pos += framer->Feed({data + pos, n - pos});
      while (framer->Next(&frame)) {
        ++totals->frames_by_mid[frame.mid];
        if (frame.mid != xs::mid::kMtData2) continue;
        if (xs::DecodeMtData2(frame.payload, &sample) != xs::MtData2Status::kOk)
          ++totals->truncated;
        Account(sample, totals);
        if (csv != nullptr) CsvRow(csv, framer->stats().frames - 1, sample);
      }
    }
  }
  framer->Flush();
  *stats = framer->stats();
  totals->bytes = stats->bytes_in;
  if (csv != nullptr) std::fclose(csv);
  return true;
}

void PrintSummary(const XsensArgs& args, const XsensTotals& t, const xs::XbusFramerStats& s) {
  std::string mids, items;
  for (const auto& [mid, n] : t.frames_by_mid) {
    mids += (mids.empty() ? "" : ", ") + Hex(mid, 2) + ": " + std::to_string(n);
  }
  for (const auto& [xdi, n] : t.items_by_xdi) {
    items += (items.empty() ? "" : ", ") + Hex(xdi, 4) + ": " + std::to_string(n);
  }
  auto opt = [](const std::optional<uint16_t>& v) {
    return v ? std::to_string(*v) : std::string("null");
  };
  std::printf(
      "{\"file\": %s, \"bytes\": %llu, \"frames\": %llu, \"frames_by_mid\": {%s}, "
      "\"checksum_errors\": %llu, \"skipped_bytes\": %llu, \"oversize\": %llu, "
      "\"mtdata2\": {\"samples\": %llu, \"truncated\": %llu, \"unknown_items\": %llu, "
      "\"bad_size_items\": %llu, \"imu_samples\": %llu, \"items_by_xdi\": {%s}}, "
      "\"counter_gaps\": %llu, \"missing_packets\": %llu, \"first_packet_counter\": %s, "
      "\"last_packet_counter\": %s}\n",
      JsonString(args.file).c_str(), static_cast<unsigned long long>(t.bytes),
      static_cast<unsigned long long>(s.frames), mids.c_str(),
      static_cast<unsigned long long>(s.checksum_errors),
      static_cast<unsigned long long>(s.skipped_bytes), static_cast<unsigned long long>(s.oversize),
      static_cast<unsigned long long>(t.samples), static_cast<unsigned long long>(t.truncated),
      static_cast<unsigned long long>(t.unknown_items),
      static_cast<unsigned long long>(t.bad_size_items),
      static_cast<unsigned long long>(t.imu_samples), items.c_str(),
      static_cast<unsigned long long>(t.counter_gaps),
      static_cast<unsigned long long>(t.missing_packets), opt(t.first_counter).c_str(),
      opt(t.last_counter).c_str());
}

int RunXsens(const XsensArgs& args) {
  XsensTotals totals;
  xs::XbusFramerStats stats;
  if (!Decode(args, &totals, &stats)) return 1;
  if (args.summary || args.csv.empty()) PrintSummary(args, totals, stats);
  return 0;
}

const DecodeCommandRegistrar kXsensCommand([](CLI::App& app, int* exit_code) {
  auto args = std::make_shared<XsensArgs>();
  CLI::App* cmd = app.add_subcommand("xsens", "Decode a raw Xbus byte log from an Xsens MTi");
  cmd->add_option("file", args->file, "raw serial bytes (.bin)")->required();
  cmd->add_flag("--summary", args->summary, "print one JSON object of counters");
  cmd->add_option("--csv", args->csv, "write the decoded MTData2 samples to this CSV file");
  cmd->callback([args, exit_code] { *exit_code = RunXsens(*args); });
});

}  // namespace
}  // namespace swlio::tools
