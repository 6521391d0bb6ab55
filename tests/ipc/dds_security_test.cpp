// DDS Security (issue 34): identities from scripts/dds-security-setup, Cyclone's builtin
// plugins. Who may read the pose and who may publish /initialpose, with the other side of each
// exchange in a swlio-echo child process (one Cyclone domain per id and process, so each
// identity needs its own process). Domains 138, 163 and 164 (134–136 are taken by the point
// cloud and echo CLI tests).
//
// Identities: daemon (publishes the outputs, reads rt/initialpose), consumer (reads the
// outputs), operator (a consumer that may publish rt/initialpose), intruder (a valid identity
// of the same CA whose permissions grant nothing of ours). "forged": the intruder's identity
// with permissions that grant the operator's topics, signed by another CA that the forger's
// own configuration trusts; only the peers' check of the permissions signature can stop it.
// "plain": the loopback XML without security.
//
// Every negative check waits exactly as the positive one that passes beside it (same child
// arguments, same sample count, same duration), so a leak would make it fail.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "child_process.h"
#include "ipc_test_util.h"
#include "swlio/ipc/participant.h"
#include "swlio/ipc/publisher.h"
#include "test_data.h"

namespace swlio::ipc {
namespace {

namespace fs = std::filesystem;

#ifdef SWLIO_HAVE_ECHO
using test_util::ChildProcess;

constexpr int kPoseDomain = 138;
constexpr int kInitialPoseDomain = 163;
constexpr int kInvalidIdentityDomain = 164;
// swlio-echo's exit codes (tools/echo/main.cpp): 0 the count was reached, 1 an error (here:
// DDS Security refused its reader), 2 the duration passed first.
constexpr int kEchoOk = 0;
constexpr int kEchoRefused = 1;
constexpr int kEchoTimedOut = 2;
constexpr const char* kCount = "20";
constexpr const char* kDuration = "15";

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void WriteFile(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

int Shell(const std::string& command) {
  const int status = std::system((command + " >/dev/null").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// Two keystores made by the script: `real` (daemon, consumer, operator, intruder) and `rogue`
/// (another CA), plus the forged configuration. Empty `skip` when usable.
struct Keystores {
  fs::path real, rogue, forged_xml;
  std::string skip;

  fs::path Xml(const std::string& identity) const {
    return real / "cyclonedds" / (identity + ".xml");
  }
};

Keystores MakeKeystores(const std::string& tag) {
  Keystores k;
  if (Shell("command -v openssl") != 0) {
    k.skip = "openssl is not installed: scripts/dds-security-setup cannot make a keystore";
    return k;
  }
  const fs::path dir = test::MakeTempDir(tag);
  k.real = dir / "keystore";
  k.rogue = dir / "rogue";
  const std::string script = (test::SourceDir() / "scripts" / "dds-security-setup").string();
  EXPECT_EQ(Shell(script + " " + k.real.string() +
                  " --identity daemon:daemon --identity consumer:consumer"
                  " --identity operator:operator --identity intruder:none"),
            0);
  EXPECT_EQ(Shell(script + " " + k.rogue.string() +
                  " --identity intruder:operator --identity consumer:consumer"),
            0);
  // The plugins the script found (an absolute path when it found Debian's directory).
  const std::string xml = ReadFile(k.Xml("daemon"));
  const std::regex library("<Library path=\"([^\"]*)\"");
  for (std::sregex_iterator it(xml.begin(), xml.end(), library), end; it != end; ++it) {
    if (!fs::exists((*it)[1].str())) {
      k.skip = "Cyclone DDS's security plugin " + (*it)[1].str() +
               " is not installed (Debian: libddsc0debian)";
      return k;
    }
  }
  if (xml.find("<Library path=\"/") == std::string::npos) {
    k.skip = "the script found no DDS Security plugin directory (Debian: libddsc0debian)";
    return k;
  }
  // The intruder's own certificate and key (issued by the real CA), the rogue CA as its
  // permissions CA, and the rogue's governance and operator permissions for CN=/swlio/intruder.
  std::string forged = ReadFile(k.Xml("intruder"));
  for (const char* file : {"permissions_ca.cert.pem", "governance.p7s", "permissions.p7s"}) {
    forged = Replace(forged, (k.real / "enclaves/swlio/intruder" / file).string(),
                     (k.rogue / "enclaves/swlio/intruder" / file).string());
  }
  k.forged_xml = dir / "forged.xml";
  WriteFile(k.forged_xml, forged);
  return k;
}

IpcConfig SecureConfig(int domain, const fs::path& xml) {
  IpcConfig config = test_util::LoopbackConfig(domain);
  config.dds_config_file = xml.string();
  return config;
}

std::vector<std::string> EchoArgs(int domain,
                                  const fs::path& xml,
                                  const std::vector<std::string>& extra) {
  // Through sh so that its stderr (where it says why it failed) joins the captured stdout.
  std::vector<std::string> args = {"/bin/sh",
                                   "-c",
                                   "exec \"$0\" \"$@\" 2>&1",
                                   ::swlio::test::ToolPath("swlio-echo").string(),
                                   "--domain",
                                   std::to_string(domain),
                                   "--dds-config",
                                   xml.string(),
                                   "--quiet",
                                   "--count",
                                   kCount,
                                   "--duration",
                                   kDuration};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

PoseWithCovarianceStamped SomePose(int i) {
  PoseWithCovarianceStamped pose;
  pose.t_ns = 1'000'000'000LL + i * 10'000'000LL;
  pose.frame_id = "map";
  pose.pose.position_m = {0.1 * i, 2.0, 0.0};
  return pose;
}

/// Everything an exited child printed.
std::string Output(ChildProcess& child) {
  std::string all, line;
  while (child.ReadLine(&line, 1.0)) all += line + "\n";
  return all;
}

/// Publishes a pose every 10 ms until every child has exited; their exit codes.
std::vector<int> PublishUntilExit(Publisher& publisher, std::vector<ChildProcess*> children) {
  std::vector<int> codes(children.size(), -1);
  std::vector<std::thread> waiters;
  std::atomic<size_t> done{0};
  for (size_t i = 0; i < children.size(); ++i) {
    waiters.emplace_back([&, i] {
      codes[i] = children[i]->Wait();
      ++done;
    });
  }
  for (int i = 0; done < children.size(); ++i) {
    publisher.PublishPose(SomePose(i));
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  for (std::thread& t : waiters) t.join();
  return codes;
}

TEST(DdsSecurity, OnlyAGrantedIdentityReadsThePose) {
  const Keystores k = MakeKeystores("dds_security_pose");
  if (!k.skip.empty()) GTEST_SKIP() << k.skip;
  const IpcConfig daemon = SecureConfig(kPoseDomain, k.Xml("daemon"));
  std::string error;
  auto participant = Participant::Create(daemon, &error);
  ASSERT_NE(participant, nullptr) << error;
  auto publisher = Publisher::Create(*participant, daemon, &error);
  ASSERT_NE(publisher, nullptr) << error;

  const std::vector<std::string> pose = {"--topics", "pose"};
  ChildProcess consumer(EchoArgs(kPoseDomain, k.Xml("consumer"), pose));
  ChildProcess intruder(EchoArgs(kPoseDomain, k.Xml("intruder"), pose));
  ChildProcess forged(EchoArgs(kPoseDomain, k.forged_xml, pose));
  ChildProcess plain(
      EchoArgs(kPoseDomain, test::SourceDir() / "config" / "cyclonedds-loopback.xml", pose));
  for (ChildProcess* c : {&consumer, &intruder, &forged, &plain}) ASSERT_TRUE(c->running());
  const std::vector<int> codes =
      PublishUntilExit(*publisher, {&consumer, &intruder, &forged, &plain});

  EXPECT_EQ(codes[0], kEchoOk) << "the consumer did not get " << kCount << " poses in " << kDuration
                               << " s";
  EXPECT_EQ(codes[1], kEchoRefused) << "the intruder's reader of rt/swlio/pose was not refused";
  const std::string said = Output(intruder);
  // Cyclone checks the permissions when the topic is created, before the reader.
  EXPECT_NE(said.find("'rt/swlio/pose': Not Allowed By Security"), std::string::npos) << said;
  EXPECT_EQ(codes[2], kEchoTimedOut) << "permissions signed by a foreign CA read the pose";
  EXPECT_EQ(codes[3], kEchoTimedOut) << "a participant without security read the pose";
}

/// Publishes rt/initialpose from a participant made from `xml` in this process until the
/// daemon's swlio-echo child exits; its exit code, or kEchoRefused when this side's writer was
/// refused (`error` then says why).
int InitialPoseFrom(const Keystores& k, const fs::path& xml, std::string* error) {
  ChildProcess daemon(EchoArgs(kInitialPoseDomain, k.Xml("daemon"),
                               {"--topics", "pose", "--pose-topic", "initialpose"}));
  EXPECT_TRUE(daemon.running());
  IpcConfig config = SecureConfig(kInitialPoseDomain, xml);
  config.pose_topic = "initialpose";
  auto participant = Participant::Create(config, error);
  EXPECT_NE(participant, nullptr) << *error;
  if (participant == nullptr) return -1;
  PublisherOptions options;
  options.topics.fill(false);
  options.topics[static_cast<size_t>(Topic::kPose)] = true;
  auto publisher = Publisher::Create(*participant, config, options, error);
  if (publisher == nullptr) return kEchoRefused;
  return PublishUntilExit(*publisher, {&daemon})[0];
}

TEST(DdsSecurity, OnlyAGrantedIdentityPublishesInitialPose) {
  const Keystores k = MakeKeystores("dds_security_initialpose");
  if (!k.skip.empty()) GTEST_SKIP() << k.skip;
  std::string error;
  EXPECT_EQ(InitialPoseFrom(k, k.Xml("operator"), &error), kEchoOk)
      << "the operator's /initialpose did not reach the daemon: " << error;
  error.clear();
  EXPECT_EQ(InitialPoseFrom(k, k.Xml("intruder"), &error), kEchoRefused);
  EXPECT_NE(error.find("Not Allowed By Security"), std::string::npos) << error;
  error.clear();
  EXPECT_EQ(InitialPoseFrom(k, k.forged_xml, &error), kEchoTimedOut)
      << "permissions signed by a foreign CA reached the daemon's reader " << error;
  EXPECT_EQ(InitialPoseFrom(k, test::SourceDir() / "config" / "cyclonedds-loopback.xml", &error),
            kEchoTimedOut)
      << "a participant without security reached the daemon's reader " << error;
}

TEST(DdsSecurity, AnInvalidIdentityIsRefusedWithAClearError) {
  const Keystores k = MakeKeystores("dds_security_invalid");
  if (!k.skip.empty()) GTEST_SKIP() << k.skip;
  const fs::path e = k.real / "enclaves/swlio/consumer";
  const std::string ca = "-CA " + (k.real / "public/ca.cert.pem").string() + " -CAkey " +
                         (k.real / "private/ca.key.pem").string();
  // A certificate for the consumer's key whose validity ended a day ago.
  ASSERT_EQ(Shell("openssl req -new -key " + (e / "key.pem").string() +
                  " -subj /CN=\\\\/swlio\\\\/consumer -out " + (e / "expired.csr").string()),
            0);
  ASSERT_EQ(Shell("openssl x509 -req -sha256 -days -1 -set_serial 7 " + ca + " -in " +
                  (e / "expired.csr").string() + " -out " + (e / "expired.pem").string()),
            0);
  const std::string xml = ReadFile(k.Xml("consumer"));
  const fs::path expired = k.real / "expired.xml";
  WriteFile(expired, Replace(xml, (e / "cert.pem").string(), (e / "expired.pem").string()));
  // A certificate and key for CN=/swlio/consumer issued by the rogue CA, against the real
  // identity CA (the permissions stay the real consumer's).
  const fs::path rogue_e = k.rogue / "enclaves/swlio/consumer";
  const fs::path foreign = k.real / "foreign.xml";
  WriteFile(foreign,
            Replace(Replace(xml, (e / "cert.pem").string(), (rogue_e / "cert.pem").string()),
                    (e / "key.pem").string(), (rogue_e / "key.pem").string()));
  const fs::path missing = k.real / "missing.xml";
  WriteFile(missing, Replace(xml, (e / "key.pem").string(), (e / "no-such-key.pem").string()));

  for (const fs::path& bad : {expired, foreign}) {
    std::string error;
    EXPECT_EQ(Participant::Create(SecureConfig(kInvalidIdentityDomain, bad), &error), nullptr)
        << bad;
    EXPECT_NE(error.find("DDS Security refused"), std::string::npos) << error;
  }
  std::string error;
  EXPECT_EQ(Participant::Create(SecureConfig(kInvalidIdentityDomain, missing), &error), nullptr);
  EXPECT_NE(
      error.find("the PrivateKey file '" + (e / "no-such-key.pem").string() + "' is not readable"),
      std::string::npos)
      << error;
  // Cyclone 0.10's access control takes domain ids up to 230 only.
  EXPECT_EQ(Participant::Create(SecureConfig(231, k.Xml("consumer")), &error), nullptr);
  EXPECT_NE(error.find("domain 231 is beyond 230"), std::string::npos) << error;
  // The same domain then takes the valid identity: the refusals left nothing behind.
  EXPECT_NE(Participant::Create(SecureConfig(kInvalidIdentityDomain, k.Xml("consumer")), &error),
            nullptr)
      << error;
}

#else
TEST(DdsSecurity, NeedsSwlioEcho) { GTEST_SKIP() << "swlio-echo is not built"; }
#endif

}  // namespace
}  // namespace swlio::ipc
