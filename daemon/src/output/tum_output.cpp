#include "swlio/daemon/output/tum_output.h"

#include <cstdio>

#include "swlio/core/lie.h"

namespace swlio::daemon {

void WriteTumLine(std::ostream& out, const State& state) {
  const Eigen::Quaterniond q = lie::PositiveW(Eigen::Quaterniond(state.T_world_imu.linear()));
  const Eigen::Vector3d p = state.T_world_imu.translation();
  char line[256];
  std::snprintf(line, sizeof line, "%lld.%09lld %.6f %.6f %.6f %.9f %.9f %.9f %.9f",
                static_cast<long long>(state.t_ns / 1'000'000'000),
                static_cast<long long>(state.t_ns % 1'000'000'000), p.x(), p.y(), p.z(), q.x(),
                q.y(), q.z(), q.w());
  out << line << '\n';
}

}  // namespace swlio::daemon
