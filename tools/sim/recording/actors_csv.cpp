#include "recording/actors_csv.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>

namespace swlio::sim {

bool WriteActorsCsv(const ActorSet& set,
                    double duration_s,
                    const std::function<int64_t(double)>& host_ns,
                    std::ostream& out) {
  out << "t_ns,id,kind,moves,x_m,y_m,z_m,yaw_rad,half_x_m,half_y_m,half_z_m\n";
  char line[256];
  for (int64_t k = 0; static_cast<double>(k) / kActorsCsvRateHz <= duration_s; ++k) {
    const double t_s = static_cast<double>(k) / kActorsCsvRateHz;
    const int64_t t_ns = host_ns(t_s);
    for (const Actor& a : set.actors()) {
      const ActorPose pose = a.At(t_s);
      const ActorPart& b = a.bounds();
      const double c = std::cos(pose.yaw_rad), s = std::sin(pose.yaw_rad);
      const Eigen::Vector3d centre =
          pose.ground_m + Eigen::Vector3d(c * b.center_m.x() - s * b.center_m.y(),
                                          s * b.center_m.x() + c * b.center_m.y(), b.center_m.z());
      std::snprintf(line, sizeof line, "%" PRId64 ",%u,%s,%d,%.4f,%.4f,%.4f,%.5f,%.3f,%.3f,%.3f\n",
                    t_ns, static_cast<unsigned>(a.id()), ActorKindName(a.plan().kind),
                    set.Moving(a.id()) ? 1 : 0, centre.x(), centre.y(), centre.z(), pose.yaw_rad,
                    b.half_m.x(), b.half_m.y(), b.half_m.z());
      out << line;
    }
  }
  return static_cast<bool>(out);
}

}  // namespace swlio::sim
