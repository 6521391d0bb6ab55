#include "scenarios/sim_dump.h"

#include <cmath>
#include <fstream>

namespace swlio::sim {

bool DumpWorldAndRoute(const SimSetup& setup,
                       const std::filesystem::path& dir,
                       std::string* error) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  std::ofstream world(dir / "world.csv");
  world << "kind,class,x,y,z,a,b,c,yaw\n";
  for (const Primitive& p : setup.world->primitives()) {
    const char* cls = ClassName(p.cls);
    switch (p.kind) {
      case Primitive::Kind::kBox:
        world << "box," << cls << ',' << p.box.center.x() << ',' << p.box.center.y() << ','
              << p.box.center.z() << ',' << p.box.half_m.x() << ',' << p.box.half_m.y() << ','
              << p.box.half_m.z() << ',' << p.box.yaw_rad << '\n';
        break;
      case Primitive::Kind::kCylinder:  // a = (x, y, z), b = (a, b, c), radius in yaw
        world << "cylinder," << cls << ',' << p.cylinder.a.x() << ',' << p.cylinder.a.y() << ','
              << p.cylinder.a.z() << ',' << p.cylinder.b.x() << ',' << p.cylinder.b.y() << ','
              << p.cylinder.b.z() << ',' << p.cylinder.radius_m << '\n';
        break;
      case Primitive::Kind::kSphere:
        world << "sphere," << cls << ',' << p.sphere.center.x() << ',' << p.sphere.center.y() << ','
              << p.sphere.center.z() << ',' << p.sphere.radius_m << ",0,0,0\n";
        break;
    }
  }
  std::ofstream route(dir / "route.csv");
  route << "t_s,x,y,z,yaw_rad,speed_mps\n";
  for (int64_t k = 0; static_cast<double>(k) * 0.1 <= SimDuration(setup); ++k) {
    const double t = static_cast<double>(k) * 0.1;
    const Kinematics kin = setup.trajectory->At(t);
    route << t << ',' << kin.p_world.x() << ',' << kin.p_world.y() << ',' << kin.p_world.z() << ','
          << std::atan2(kin.R_world_body(1, 0), kin.R_world_body(0, 0)) << ',' << kin.v_world.norm()
          << '\n';
  }
  if (!world || !route) {
    *error = "cannot write world.csv / route.csv in " + dir.string();
    return false;
  }
  return true;
}

}  // namespace swlio::sim
