// swlio-decode can FILE.log: reads a candump log (candump_log.h), counts frames per identifier
// and, given the chassis odometry layout (from the daemon's YAML via --config, or from
// --signal flags), decodes wheel-odometry samples.
//
//   swlio-decode can drive.log --summary --config /etc/swlio/swlio.yaml
//   swlio-decode can drive.log --summary --csv odom.csv
//     --signal role=left_wheel_speed,id=0x201,byte_offset=0,length_bits=16,scale=0.001
//     --signal role=right_wheel_speed,id=0x201,byte_offset=2,length_bits=16,scale=0.001

#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "decode_command.h"
#include "swlio/daemon/config/config_loader.h"
#include "swlio/drivers/candump_log.h"
#include "swlio/drivers/wheel_odom_decoder.h"

namespace swlio::tools {
namespace {

struct CanOptions {
  std::string file;
  bool summary = false;
  std::string csv;
  std::string config;
  std::vector<std::string> signals;
  drivers::CanConfig layout;  ///< geometry and mode flags land here directly
};

bool ParseNumber(const std::string& text, int64_t* out) {
  try {
    size_t used = 0;
    *out = std::stoll(text, &used, 0);  // base 0: decimal or 0x hex
    return used == text.size();
  } catch (const std::exception&) {
    return false;
  }
}

bool ParseReal(const std::string& text, double* out) {
  try {
    size_t used = 0;
    *out = std::stod(text, &used);
    return used == text.size();
  } catch (const std::exception&) {
    return false;
  }
}

/// "role=…,id=…,start_bit=…|byte_offset=…,length_bits=…,order=intel|motorola,signed=0|1,
/// extended=0|1,scale=…,offset=…,dlc=…" → a signal; false with a reason on error.
bool ParseSignalSpec(const std::string& spec, drivers::CanSignalConfig* s, std::string* error) {
  std::stringstream items(spec);
  std::string item;
  while (std::getline(items, item, ',')) {
    const size_t eq = item.find('=');
    const std::string key = item.substr(0, eq);
    const std::string value = eq == std::string::npos ? "" : item.substr(eq + 1);
    int64_t n = 0;
    bool ok = true;
    if (key == "role") {
      s->role = value;
    } else if (key == "order" || key == "byte_order") {
      s->byte_order = value;
    } else if (key == "scale") {
      ok = ParseReal(value, &s->scale);
    } else if (key == "offset") {
      ok = ParseReal(value, &s->offset);
    } else if (key == "signed" || key == "extended") {
      ok = ParseNumber(value, &n) && (n == 0 || n == 1);
      (key == "signed" ? s->is_signed : s->extended) = n == 1;
    } else if (key == "id" || key == "can_id" || key == "start_bit" || key == "byte_offset" ||
               key == "length_bits" || key == "dlc") {
      ok = ParseNumber(value, &n);
      int64_t& field = key == "start_bit"     ? s->start_bit
                       : key == "byte_offset" ? s->byte_offset
                       : key == "length_bits" ? s->length_bits
                       : key == "dlc"         ? s->dlc
                                              : s->can_id;
      field = n;
    } else {
      ok = false;
    }
    if (!ok) {
      *error = "--signal: cannot use '" + item + "'";
      return false;
    }
  }
  return true;
}

/// The layout from --config or --signal flags; std::nullopt (and no error) when neither given.
std::optional<drivers::CanConfig> Layout(const CanOptions& o, std::string* error) {
  if (!o.config.empty()) {
    const daemon::LoadedConfig loaded = daemon::LoadConfigFile(o.config);
    if (!loaded.ok()) {
      *error = loaded.ErrorReport();
      return std::nullopt;
    }
    if (loaded.config.can.signals.empty()) *error = o.config + ": no can.signals layout";
    return loaded.config.can;
  }
  if (o.signals.empty()) return std::nullopt;
  drivers::CanConfig c = o.layout;
  for (const std::string& spec : o.signals) {
    if (!ParseSignalSpec(spec, &c.signals.emplace_back(), error)) return std::nullopt;
  }
  return c;
}

std::string IdKey(const drivers::CanFrame& f) {
  char buf[16];
  std::snprintf(buf, sizeof(buf), f.extended || f.error ? "0x%08X" : "0x%03X", f.id);
  return buf;
}

struct Tally {
  uint64_t remote = 0;
  uint64_t error = 0;
  int64_t first_t_ns = -1;
  int64_t last_t_ns = -1;
  std::map<std::pair<int, std::string>, uint64_t> by_id;  ///< (kind, "0x…") → frames
  uint64_t samples = 0;
};

void PrintSummary(const Tally& t,
                  const drivers::CandumpCounters& log,
                  const drivers::WheelOdomDecoder* decoder) {
  std::ostringstream os;
  os << "{\"lines\": " << log.lines << ", \"frames\": " << log.frames
     << ", \"malformed_lines\": " << log.malformed_lines
     << ", \"can_fd_lines\": " << log.can_fd_lines << ", \"blank_lines\": " << log.blank_lines
     << ", \"remote_frames\": " << t.remote << ", \"error_frames\": " << t.error
     << ", \"first_t_ns\": " << t.first_t_ns << ", \"last_t_ns\": " << t.last_t_ns
     << ", \"frames_by_id\": {";
  const char* sep = "";
  for (const auto& [key, count] : t.by_id) {
    os << sep << '"' << (key.first == 2 ? "error:" : "") << key.second << "\": " << count;
    sep = ", ";
  }
  os << "}, \"samples\": " << t.samples;
  if (decoder != nullptr) {
    const drivers::WheelOdomCounters& c = decoder->counters();
    os << ", \"decoder\": {\"frames_used\": " << c.frames_used
       << ", \"unknown_id\": " << c.unknown_id << ", \"bad_dlc\": " << c.bad_dlc
       << ", \"remote_or_error\": " << c.remote_or_error
       << ", \"unpaired_dropped\": " << c.unpaired_dropped << "}";
  }
  os << "}\n";
  std::cout << os.str();
}

int Run(const CanOptions& o) {
  std::string error;
  const std::optional<drivers::CanConfig> layout = Layout(o, &error);
  if (!error.empty()) {
    std::cerr << "swlio-decode can: " << error << "\n";
    return 2;
  }
  std::optional<drivers::WheelOdomDecoder> decoder;
  if (layout) {
    ConfigIssues issues;
    decoder = drivers::WheelOdomDecoder::Create(*layout, &issues);
    for (const auto& i : issues)
      std::cerr << "swlio-decode can: " << i.key << ": " << i.reason << "\n";
    if (!decoder) return 2;
  }
  if (!o.csv.empty() && !decoder) {
    std::cerr << "swlio-decode can: --csv needs a layout (--config or --signal)\n";
    return 2;
  }
  std::ifstream in(o.file, std::ios::binary);
  if (!in) {
    std::cerr << "swlio-decode can: cannot open " << o.file << "\n";
    return 1;
  }
  std::ofstream csv;
  if (!o.csv.empty()) {
    csv.open(o.csv);
    if (!csv) {
      std::cerr << "swlio-decode can: cannot write " << o.csv << "\n";
      return 1;
    }
    csv << "t_ns,linear_velocity_mps,yaw_rate_radps,left_wheel_mps,right_wheel_mps\n";
    csv.precision(9);
  }
  drivers::CandumpReader reader(in);
  drivers::CandumpRecord r;
  Tally t;
  while (reader.Next(&r)) {
    const drivers::CanFrame& f = r.frame;
    t.remote += f.remote ? 1 : 0;
    t.error += f.error ? 1 : 0;
    if (t.first_t_ns < 0) t.first_t_ns = r.t_ns;
    t.last_t_ns = r.t_ns;
    ++t.by_id[{f.error ? 2 : (f.extended ? 1 : 0), IdKey(f)}];
    if (!decoder) continue;
    const std::optional<drivers::WheelOdomSample> s = decoder->Decode(f, r.t_ns);
    if (!s) continue;
    ++t.samples;
    if (csv.is_open()) {
      csv << s->t_ns << ',' << s->linear_velocity_mps << ',' << s->yaw_rate_radps << ',';
      if (s->has_wheel_speeds)
        csv << s->left_wheel_mps << ',' << s->right_wheel_mps;
      else
        csv << ',';
      csv << '\n';
    }
  }
  if (o.summary) PrintSummary(t, reader.counters(), decoder ? &*decoder : nullptr);
  return 0;
}

void AddCanCommand(CLI::App& app, int* exit_code) {
  auto o = std::make_shared<CanOptions>();
  CLI::App* cmd = app.add_subcommand("can", "Decode a candump log (wheel odometry)");
  cmd->add_option("file", o->file, "candump log (candump -l format)")->required();
  cmd->add_flag("--summary", o->summary, "print one JSON object with counts");
  cmd->add_option("--csv", o->csv, "write the odometry samples to this CSV file");
  cmd->add_option("--config", o->config, "take the layout from this swliod YAML (can: section)");
  cmd->add_option("--signal", o->signals,
                  "signal layout, repeatable: role=…,id=…,start_bit=…|byte_offset=…,"
                  "length_bits=…,order=intel|motorola,signed=0|1,extended=0|1,scale=…,offset=…,"
                  "dlc=…")
      ->excludes(cmd->get_option("--config"));
  cmd->add_option("--mode", o->layout.mode, "wheel_speeds | twist (with --signal)");
  cmd->add_option("--wheel-speed-unit", o->layout.wheel_speed_unit, "mps | radps");
  cmd->add_option("--wheel-radius", o->layout.wheel_radius_m, "metres (radps only)");
  cmd->add_option("--track-width", o->layout.track_width_m, "metres between the wheels");
  cmd->add_option("--max-pair-skew", o->layout.max_pair_skew_s, "seconds");
  cmd->callback([o, exit_code] { *exit_code = Run(*o); });
}

const DecodeCommandRegistrar kCanRegistrar(AddCanCommand);

}  // namespace
}  // namespace swlio::tools
