#pragma once
/// @file
/// The result type of every config struct's `Validate()`: one entry per violated rule, keyed
/// by the field's name inside its section (the loader adds the section, file and line).

#include <sstream>
#include <string>
#include <vector>

namespace swlio {

struct ConfigIssue {
  std::string key;     ///< field name relative to its section, e.g. "max_range_m"
  std::string reason;  ///< human-readable rule that was violated
};

using ConfigIssues = std::vector<ConfigIssue>;

/// Appends an issue unless lo ≤ value ≤ hi.
template <typename T>
void CheckInRange(ConfigIssues& issues, const std::string& key, T value, T lo, T hi) {
  if (value >= lo && value <= hi) return;
  std::ostringstream os;
  os << "must be in [" << lo << ", " << hi << "], got " << value;
  issues.push_back({key, os.str()});
}

/// Appends an issue unless value > 0.
template <typename T>
void CheckPositive(ConfigIssues& issues, const std::string& key, T value) {
  if (value > T{0}) return;
  std::ostringstream os;
  os << "must be > 0, got " << value;
  issues.push_back({key, os.str()});
}

/// Appends an issue when `condition` is false.
inline void CheckThat(ConfigIssues& issues,
                      bool condition,
                      const std::string& key,
                      const std::string& reason) {
  if (!condition) issues.push_back({key, reason});
}

/// Prefixes every key of `inner` with `section.` and appends it to `out`.
inline void AppendWithPrefix(ConfigIssues& out,
                             const std::string& section,
                             const ConfigIssues& inner) {
  for (const auto& issue : inner) out.push_back({section + "." + issue.key, issue.reason});
}

}  // namespace swlio
