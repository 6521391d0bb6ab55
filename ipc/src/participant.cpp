#include "swlio/ipc/participant.h"

#include <dds/dds.h>

#include <fstream>
#include <map>
#include <mutex>
#include <regex>
#include <sstream>

namespace swlio::ipc {
namespace {

/// Domains this process created from a checked configuration, with their participant counts.
/// Cyclone allows one dds_create_domain per id and process; later participants share it.
struct DomainRegistry {
  std::mutex mutex;
  std::map<uint32_t, std::pair<dds_entity_t, int>> domains;  // id → (domain handle, users)
};

DomainRegistry& Registry() {
  static DomainRegistry registry;
  return registry;
}

bool IsLoopbackAddress(const std::string& a) {
  return a == "lo" || a == "127.0.0.1" || a == "localhost" || a.rfind("127.0.0.1:", 0) == 0 ||
         a.rfind("localhost:", 0) == 0;
}

/// Every value of attribute `attr` on elements `tag` must be a loopback address.
bool AllAttributesLoopback(const std::string& xml,
                           const std::string& tag,
                           const std::string& attr,
                           int* count,
                           std::string* why) {
  const std::regex element("<" + tag + "\\b([^>]*)>");
  const std::regex attribute(attr + "\\s*=\\s*\"([^\"]*)\"");
  *count = 0;
  for (std::sregex_iterator it(xml.begin(), xml.end(), element), end; it != end; ++it) {
    const std::string attrs = (*it)[1].str();
    std::smatch m;
    ++*count;
    if (!std::regex_search(attrs, m, attribute) || !IsLoopbackAddress(m[1].str())) {
      *why = "<" + tag + (*it)[1].str() + "> is not loopback";
      return false;
    }
  }
  return true;
}

}  // namespace

// Cyclone 0.10's <Security>: <Authentication> IdentityCA, IdentityCertificate, PrivateKey;
// <AccessControl> PermissionsCA, Governance, Permissions; each a "file:" path or inline "data:,".
std::string UnreadableDdsSecurityFile(const std::string& xml) {
  const std::regex file_re(
      "<(IdentityCA|IdentityCertificate|PrivateKey|PermissionsCA|Governance|Permissions)>\\s*"
      "file:([^<]*?)\\s*<");
  for (std::sregex_iterator it(xml.begin(), xml.end(), file_re), end; it != end; ++it) {
    if (!std::ifstream((*it)[2].str())) {
      return "DDS Security: the " + (*it)[1].str() + " file '" + (*it)[2].str() +
             "' is not readable";
    }
  }
  return "";
}

bool HasDdsSecurity(const std::string& xml) {
  return std::regex_search(xml, std::regex("<Security\\b"));
}

bool IsLoopbackOnlyConfig(const std::string& xml, std::string* why) {
  std::string reason;
  int interfaces = 0;
  int peers = 0;
  int legacy = 0;
  bool ok =
      AllAttributesLoopback(xml, "NetworkInterface", "(?:name|address)", &interfaces, &reason) &&
      AllAttributesLoopback(xml, "Peer", "address", &peers, &reason);
  const std::regex legacy_re("<NetworkInterfaceAddress>\\s*([^<\\s]*)\\s*<");
  for (std::sregex_iterator it(xml.begin(), xml.end(), legacy_re), end; ok && it != end; ++it) {
    ++legacy;
    if (!IsLoopbackAddress((*it)[1].str())) {
      ok = false;
      reason = "NetworkInterfaceAddress " + (*it)[1].str() + " is not loopback";
    }
  }
  if (ok && interfaces + legacy == 0) {
    ok = false;
    reason = "no NetworkInterface is named: Cyclone would pick an external interface";
  }
  if (ok && !std::regex_search(xml, std::regex("<AllowMulticast>\\s*false\\s*</AllowMulticast>"))) {
    ok = false;
    reason = "AllowMulticast is not false";
  }
  if (ok && peers == 0) {
    ok = false;
    reason = "no <Peer address=\"127.0.0.1\"/>: unicast discovery would find nobody";
  }
  if (!ok && why != nullptr) *why = reason;
  return ok;
}

std::unique_ptr<Participant> Participant::Create(const IpcConfig& config, std::string* error) {
  auto fail = [&](const std::string& message) {
    if (error != nullptr) *error = message;
    return std::unique_ptr<Participant>();
  };
  std::ifstream in(config.dds_config_file);
  if (!in) return fail("cannot read DDS configuration '" + config.dds_config_file + "'");
  std::ostringstream xml;
  xml << in.rdbuf();
  std::string why;
  if (config.require_loopback && !IsLoopbackOnlyConfig(xml.str(), &why)) {
    return fail("refusing to start DDS: '" + config.dds_config_file + "': " + why);
  }
  const bool secure = HasDdsSecurity(xml.str());
  if (secure) {
    const std::string unreadable = UnreadableDdsSecurityFile(xml.str());
    if (!unreadable.empty()) return fail("'" + config.dds_config_file + "': " + unreadable);
    if (config.domain_id > kMaxDdsSecurityDomainId) {
      return fail("DDS Security: domain " + std::to_string(config.domain_id) + " is beyond " +
                  std::to_string(kMaxDdsSecurityDomainId) +
                  ", the largest id Cyclone 0.10's access control takes");
    }
  }

  const auto domain_id = static_cast<uint32_t>(config.domain_id);
  DomainRegistry& registry = Registry();
  std::lock_guard<std::mutex> lock(registry.mutex);
  auto it = registry.domains.find(domain_id);
  if (it == registry.domains.end()) {
    const dds_entity_t domain = dds_create_domain(domain_id, xml.str().c_str());
    if (domain < 0) {
      return fail("cannot create DDS domain " + std::to_string(domain_id) + ": " +
                  dds_strretcode(domain) +
                  " (it may already exist in this process with another configuration)");
    }
    it = registry.domains.emplace(domain_id, std::make_pair(domain, 0)).first;
  }
  const dds_entity_t participant = dds_create_participant(domain_id, nullptr, nullptr);
  if (participant < 0) {
    if (it->second.second == 0) {
      dds_delete(it->second.first);
      registry.domains.erase(it);
    }
    std::string message =
        std::string("cannot create DDS participant: ") + dds_strretcode(participant);
    if (secure) {
      // Cyclone logs the reason (stderr): a plugin library that does not load, an identity
      // certificate that has expired or was not issued by the identity CA, a key that is not
      // the certificate's, a governance or permissions document not signed by the permissions
      // CA, or a grant whose subject or validity does not fit the certificate.
      message += ": DDS Security refused the plugins, the identity or its documents named in '" +
                 config.dds_config_file + "' (Cyclone's log line above says which)";
    }
    return fail(message);
  }
  ++it->second.second;
  return std::unique_ptr<Participant>(new Participant(participant, domain_id));
}

Participant::~Participant() {
  dds_delete(participant_);
  DomainRegistry& registry = Registry();
  std::lock_guard<std::mutex> lock(registry.mutex);
  auto it = registry.domains.find(domain_id_);
  if (it != registry.domains.end() && --it->second.second == 0) {
    dds_delete(it->second.first);
    registry.domains.erase(it);
  }
}

}  // namespace swlio::ipc
