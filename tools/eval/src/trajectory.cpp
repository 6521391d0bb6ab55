// Readers and writers of TUM and KITTI trajectory files; see trajectory.h for the formats.

#include "swlio/eval/trajectory.h"

#include <Eigen/Geometry>

#include <charconv>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string_view>

namespace swlio::eval {
namespace {

/// Error "name:line: what".
[[noreturn]] void Fail(const std::string& name, std::size_t line, const std::string& what) {
  std::ostringstream os;
  os << name << ':' << line << ": " << what;
  throw EvalError(os.str());
}

/// Splits `line` at spaces, tabs and commas and parses every field as a finite double.
std::vector<double> ParseNumbers(std::string_view line, const std::string& name, std::size_t no) {
  std::vector<double> values;
  std::size_t i = 0;
  const auto is_sep = [](char c) { return c == ' ' || c == '\t' || c == ',' || c == '\r'; };
  while (i < line.size()) {
    while (i < line.size() && is_sep(line[i])) ++i;
    if (i >= line.size()) break;
    std::size_t end = i;
    while (end < line.size() && !is_sep(line[end])) ++end;
    const std::string_view field = line.substr(i, end - i);
    double value = 0.0;
    const char* first = field.data();
    if (!field.empty() && field.front() == '+') ++first;  // from_chars rejects a leading '+'
    const auto [ptr, ec] = std::from_chars(first, field.data() + field.size(), value);
    if (ec != std::errc() || ptr != field.data() + field.size()) {
      Fail(name, no,
           "field " + std::to_string(values.size() + 1) + " ('" + std::string(field) +
               "') is not a number");
    }
    if (!std::isfinite(value)) {
      Fail(name, no, "field " + std::to_string(values.size() + 1) + " is not finite");
    }
    values.push_back(value);
    i = end;
  }
  return values;
}

/// True for lines without data: empty, blank or a `#` comment.
bool IsSkippable(std::string_view line) {
  const auto first = line.find_first_not_of(" \t\r");
  return first == std::string_view::npos || line[first] == '#';
}

/// Calls `row(values, line_no)` for every data line.
template <typename RowFn>
void ForEachRow(std::istream& in, const std::string& name, RowFn&& row) {
  std::string line;
  std::size_t no = 0;
  while (std::getline(in, line)) {
    ++no;
    if (IsSkippable(line)) continue;
    row(ParseNumbers(line, name, no), no);
  }
  if (in.bad()) throw EvalError(name + ": read error");
}

std::ifstream OpenOrThrow(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw EvalError(path.string() + ": cannot open file");
  return in;
}

}  // namespace

Trajectory Trajectory::Select(const std::vector<std::size_t>& ids) const {
  Trajectory out;
  out.poses.reserve(ids.size());
  for (std::size_t id : ids) out.poses.push_back(poses.at(id));
  if (HasStamps()) {
    out.stamps_s.reserve(ids.size());
    for (std::size_t id : ids) out.stamps_s.push_back(stamps_s.at(id));
  }
  return out;
}

double Trajectory::PathLength() const {
  double length_m = 0.0;
  for (std::size_t i = 1; i < poses.size(); ++i) length_m += (Position(i) - Position(i - 1)).norm();
  return length_m;
}

Eigen::Matrix3d RotationFromQuaternion(double w, double x, double y, double z) {
  const double n2 = w * w + x * x + y * y + z * z;
  if (!(n2 > std::numeric_limits<double>::epsilon())) {
    throw EvalError("quaternion has zero norm");
  }
  return Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
}

Trajectory ParseTum(std::istream& in, const std::string& name) {
  Trajectory traj;
  ForEachRow(in, name, [&](const std::vector<double>& v, std::size_t no) {
    if (v.size() != 8) {
      Fail(name, no,
           "expected 8 numbers (timestamp tx ty tz qx qy qz qw), got " + std::to_string(v.size()));
    }
    Pose T = Pose::Identity();
    try {
      T.block<3, 3>(0, 0) = RotationFromQuaternion(v[7], v[4], v[5], v[6]);
    } catch (const EvalError& e) {
      Fail(name, no, e.what());
    }
    T.block<3, 1>(0, 3) << v[1], v[2], v[3];
    traj.stamps_s.push_back(v[0]);
    traj.poses.push_back(T);
  });
  if (traj.Size() == 0) throw EvalError(name + ": no poses");
  return traj;
}

Trajectory ParseKitti(std::istream& in, const std::string& name) {
  Trajectory traj;
  ForEachRow(in, name, [&](const std::vector<double>& v, std::size_t no) {
    if (v.size() != 12) {
      Fail(name, no,
           "expected 12 numbers (3×4 pose matrix, row-major), got " + std::to_string(v.size()));
    }
    Pose T = Pose::Identity();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c)
        T(r, c) = v[4 * static_cast<std::size_t>(r) + static_cast<std::size_t>(c)];
    }
    traj.poses.push_back(T);
  });
  if (traj.Size() == 0) throw EvalError(name + ": no poses");
  return traj;
}

std::vector<double> ParseTimes(std::istream& in, const std::string& name) {
  std::vector<double> stamps_s;
  ForEachRow(in, name, [&](const std::vector<double>& v, std::size_t no) {
    if (v.size() != 1) {
      Fail(name, no, "expected 1 number (time in seconds), got " + std::to_string(v.size()));
    }
    stamps_s.push_back(v[0]);
  });
  return stamps_s;
}

Trajectory ReadTumFile(const std::filesystem::path& path) {
  std::ifstream in = OpenOrThrow(path);
  return ParseTum(in, path.string());
}

Trajectory ReadKittiFile(const std::filesystem::path& path,
                         const std::filesystem::path& times_path) {
  std::ifstream in = OpenOrThrow(path);
  Trajectory traj = ParseKitti(in, path.string());
  if (!times_path.empty()) {
    std::ifstream times_in = OpenOrThrow(times_path);
    traj.stamps_s = ParseTimes(times_in, times_path.string());
    if (traj.stamps_s.size() != traj.Size()) {
      throw EvalError(times_path.string() + ": has " + std::to_string(traj.stamps_s.size()) +
                      " times but " + path.string() + " has " + std::to_string(traj.Size()) +
                      " poses");
    }
  }
  return traj;
}

void WriteTum(std::ostream& out, const Trajectory& trajectory) {
  if (!trajectory.HasStamps()) throw EvalError("WriteTum: trajectory has no stamps");
  out << std::setprecision(17);
  for (std::size_t i = 0; i < trajectory.Size(); ++i) {
    const Eigen::Quaterniond q(Eigen::Matrix3d(trajectory.poses[i].block<3, 3>(0, 0)));
    const Eigen::Vector3d p = trajectory.Position(i);
    out << trajectory.stamps_s[i] << ' ' << p.x() << ' ' << p.y() << ' ' << p.z() << ' ' << q.x()
        << ' ' << q.y() << ' ' << q.z() << ' ' << q.w() << '\n';
  }
}

void WriteKitti(std::ostream& out, const Trajectory& trajectory) {
  out << std::setprecision(17);
  for (const Pose& T : trajectory.poses) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) out << T(r, c) << ((r == 2 && c == 3) ? '\n' : ' ');
    }
  }
}

}  // namespace swlio::eval
