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
  if (ipc::HasDdsSecurity(xml.str())) {
    const std::string unreadable = ipc::UnreadableDdsSecurityFile(xml.str());
    if (!unreadable.empty()) {
      problems.push_back("ipc.dds_config_file: '" + xml_path + "': " + unreadable);
    }
    if (config.ipc.domain_id > ipc::kMaxDdsSecurityDomainId) {
      problems.push_back("ipc.domain_id: " + std::to_string(config.ipc.domain_id) +
                         " is beyond 230, the largest id DDS Security (Cyclone 0.10) takes");
    }
  }
  return problems;
}

}  // namespace swlio::daemon
