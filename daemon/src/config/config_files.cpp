#include "swlio/daemon/config/config_files.h"

#include <fstream>
#include <sstream>

#include "swlio/ipc/participant.h"

namespace swlio::daemon {

std::vector<std::string> CheckReferencedFiles(const DaemonConfig& config) {
  std::vector<std::string> problems;
  const std::string& xml_path = config.ipc.dds_config_file;
  std::ifstream in(xml_path, std::ios::binary);
  if (!in) {
    problems.push_back("ipc.dds_config_file: cannot read '" + xml_path + "'");
    return problems;
  }
  std::ostringstream xml;
  xml << in.rdbuf();
  std::string why;
  if (config.ipc.require_loopback && !ipc::IsLoopbackOnlyConfig(xml.str(), &why)) {
    problems.push_back("ipc.dds_config_file: '" + xml_path + "' is not loopback-only (" + why +
                       ") while ipc.require_loopback is true");
  }
  return problems;
}

}  // namespace swlio::daemon
