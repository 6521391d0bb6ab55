// One-line JSON of evaluation results (see json.h).

#include "swlio/eval/json.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace swlio::eval {

std::string FormatExact(double value) {
  if (!std::isfinite(value)) return "null";
  char buf[40];
  std::snprintf(buf, sizeof(buf), "%.17g", value);
  return buf;
}

std::string ToJson(const Statistics& s) {
  std::ostringstream out;
  out << "{\"n\": " << s.n << ", \"max\": " << FormatExact(s.max)
      << ", \"mean\": " << FormatExact(s.mean) << ", \"median\": " << FormatExact(s.median)
      << ", \"min\": " << FormatExact(s.min) << ", \"rmse\": " << FormatExact(s.rmse)
      << ", \"sse\": " << FormatExact(s.sse) << ", \"std\": " << FormatExact(s.std) << "}";
  return out.str();
}

std::string ToJson(const KittiResult& r) {
  std::ostringstream out;
  out << "{\"n_segments\": " << r.segments.size()
      << ", \"t_err_percent\": " << FormatExact(r.t_err_percent)
      << ", \"r_err_deg_per_100m\": " << FormatExact(r.r_err_deg_per_100m) << ", \"per_length\": [";
  for (std::size_t i = 0; i < r.per_length.size(); ++i) {
    const KittiLengthSummary& l = r.per_length[i];
    out << (i ? ", " : "") << "{\"length_m\": " << FormatExact(l.length_m) << ", \"n\": " << l.n
        << ", \"t_err_percent\": " << FormatExact(l.t_err_percent)
        << ", \"r_err_deg_per_100m\": " << FormatExact(l.r_err_deg_per_100m) << "}";
  }
  out << "]}";
  return out.str();
}

}  // namespace swlio::eval
