#pragma once
/// @file
/// A Cyclone DDS domain participant that is always created from an explicit XML configuration,
/// never from Cyclone's defaults (which pick the first external interface and multicast).

#include <cstdint>
#include <memory>
#include <string>

#include "swlio/ipc/ipc_config.h"

namespace swlio::ipc {

/// Checks that a Cyclone DDS XML configuration keeps traffic on loopback: every
/// NetworkInterface is "lo" / 127.0.0.1, multicast is disallowed, and every discovery peer is
/// 127.0.0.1 / localhost. Returns false with the reason in `why` otherwise.
bool IsLoopbackOnlyConfig(const std::string& xml, std::string* why);

/// True when a Cyclone DDS XML turns DDS Security on (a `<Security>` section;
/// docs/dds-security.md).
bool HasDdsSecurity(const std::string& xml);

/// The first DDS Security file that a Cyclone DDS XML names ("file:" paths of IdentityCA,
/// IdentityCertificate, PrivateKey, PermissionsCA, Governance, Permissions) and that cannot be
/// read, as a message naming it; empty when all can. Whether their contents are valid only the
/// plugins can tell, when the participant is created.
std::string UnreadableDdsSecurityFile(const std::string& xml);

/// The largest domain id with DDS Security: Cyclone 0.10's access-control plugin refuses any
/// larger id in governance and permissions documents (access_control_parser.c).
inline constexpr int64_t kMaxDdsSecurityDomainId = 230;

class Participant {
 public:
  /// Creates the DDS domain `config.domain_id` from `config.dds_config_file` and a participant in
  /// it. Refuses (nullptr, `error` filled) when the file is unreadable, when `require_loopback`
  /// is set and the XML is not loopback-only, or when the domain already exists in this process
  /// with a configuration that was not created here.
  ///
  /// DDS Security (a `<Security>` section, docs/dds-security.md): a file it names that cannot be
  /// read is refused by name; an identity or document the plugins refuse (expired or foreign
  /// certificate, wrong key, unsigned or mismatching governance/permissions) fails here with
  /// an error that says so, the plugin's reason being on Cyclone's log (stderr).
  static std::unique_ptr<Participant> Create(const IpcConfig& config, std::string* error);

  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  /// The Cyclone entity handle (dds_entity_t), for writers and readers inside ipc/.
  int32_t handle() const { return participant_; }
  uint32_t domain_id() const { return domain_id_; }

 private:
  Participant(int32_t participant, uint32_t domain_id)
      : participant_(participant), domain_id_(domain_id) {}

  int32_t participant_;
  uint32_t domain_id_;
};

}  // namespace swlio::ipc
