#include "swlio/daemon/state/time_offset_state.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include "swlio/estimator/common/replace_file.h"

namespace swlio::daemon {
namespace {

constexpr const char* kFormat = "swlio-time-offset 1";
constexpr std::uintmax_t kMaxFileBytes = 65'536;  // the file is ~200 bytes

template <typename T>
bool Number(const YAML::Node& root, const char* key, T* out, std::string* error) {
  const YAML::Node node = root[key];
  if (!node || !node.IsScalar()) {
    *error = std::string(key) + ": missing, or not a number";
    return false;
  }
  const std::string& text = node.Scalar();
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, *out);
  if (ec != std::errc() || ptr != end) {
    *error = std::string(key) + ": '" + text + "' is not a number";
    return false;
  }
  return true;
}

std::optional<SavedTimeOffset> Check(const SavedTimeOffset& s, std::string* error) {
  if (!std::isfinite(s.offset_s) || std::abs(s.offset_s) > kMaxSavedTimeOffsetS) {
    *error = "offset_s: must be finite and within ±0.2 s";
  } else if (!(s.sigma_s >= 1e-9 && s.sigma_s <= kMaxSavedTimeOffsetS)) {
    *error = "sigma_s: must be positive, from 1 ns to 0.2 s";
  } else if (s.updates == 0) {
    *error = "updates: must be at least 1 (only an estimate that passed its gate is kept)";
  } else if (s.saved_utc.size() > 40 ||
             !std::all_of(s.saved_utc.begin(), s.saved_utc.end(), [](char c) {
               return std::isalnum(static_cast<unsigned char>(c)) || std::strchr(":+-.", c);
             })) {
    *error = "saved_utc: not a time (ISO 8601, as swliod writes it)";
  } else {
    return s;
  }
  return std::nullopt;
}

}  // namespace

std::string FormatTimeOffsetState(const SavedTimeOffset& saved) {
  char text[512];
  std::snprintf(text, sizeof(text),
                "# The LiDAR-IMU time offset swliod estimated online (state.time_offset_file):\n"
                "# its next start begins here. Delete the file to start from\n"
                "# estimator.window.time_offset.initial_offset_s again.\n"
                "format: %s\noffset_s: %.9g\nsigma_s: %.6g\nupdates: %llu\nsaved_utc: \"%s\"\n",
                kFormat, saved.offset_s, saved.sigma_s,
                static_cast<unsigned long long>(saved.updates), saved.saved_utc.c_str());
  return text;
}

std::optional<SavedTimeOffset> ParseTimeOffsetState(const std::string& text, std::string* error) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    *error = std::string("not YAML: ") + e.what();
    return std::nullopt;
  }
  if (!root.IsMap()) {
    *error = "not a map of keys to values";
    return std::nullopt;
  }
  const std::set<std::string> known = {"format", "offset_s", "sigma_s", "updates", "saved_utc"};
  for (const auto& kv : root) {
    const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : "?";
    if (known.count(key) == 0) {
      *error = key + ": unknown key";
      return std::nullopt;
    }
  }
  const YAML::Node format = root["format"];
  if (!format || !format.IsScalar() || format.Scalar() != kFormat) {
    *error = std::string("format: expected '") + kFormat + "'";
    return std::nullopt;
  }
  SavedTimeOffset s;
  if (!Number(root, "offset_s", &s.offset_s, error) ||
      !Number(root, "sigma_s", &s.sigma_s, error) || !Number(root, "updates", &s.updates, error))
    return std::nullopt;
  if (const YAML::Node utc = root["saved_utc"]; utc && utc.IsScalar()) s.saved_utc = utc.Scalar();
  return Check(s, error);
}

std::optional<SavedTimeOffset> ReadTimeOffsetState(const std::filesystem::path& path,
                                                   std::string* error) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) {
    *error = path.string() + ": " + ec.message();
    return std::nullopt;
  }
  if (size > kMaxFileBytes) {
    *error = path.string() + ": " + std::to_string(size) + " bytes, not a time offset file";
    return std::nullopt;
  }
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) {
    *error = path.string() + ": cannot read";
    return std::nullopt;
  }
  std::optional<SavedTimeOffset> saved = ParseTimeOffsetState(text.str(), error);
  if (!saved) *error = path.string() + ": " + *error;
  return saved;
}

bool WriteTimeOffsetState(const std::filesystem::path& path,
                          const SavedTimeOffset& saved,
                          std::string* error) {
  const std::string text = FormatTimeOffsetState(saved);
  return estimator::ReplaceFile(
      path.string(), path.string(),
      [&](std::ostream& out, std::string* why) {
        if (out << text) return true;
        *why = path.string() + ": write failed";
        return false;
      },
      error);
}

}  // namespace swlio::daemon
