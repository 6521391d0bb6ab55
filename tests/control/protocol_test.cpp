// The control protocol (swlio/control/protocol.h, docs/control.md): requests as swlioctl sends
// them parse back; malformed input of every kind is refused with a reason; the reply grammar
// round-trips; the line reader bounds what a client can make the daemon hold.

#include "swlio/control/protocol.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace swlio::control {
namespace {

using ::testing::HasSubstr;

std::string Refusal(std::string_view line) {
  std::string error;
  const std::optional<Request> r = ParseRequest(line, &error);
  EXPECT_FALSE(r.has_value()) << "'" << line << "' parsed";
  EXPECT_FALSE(error.empty());
  return error;
}

TEST(ControlProtocol, RequestsRoundTrip) {
  for (const Request& r :
       {Request{Command::kStatus, ""}, Request{Command::kReset, ""},
        Request{Command::kSaveMap, "/var/lib/swlio/site A.map"},
        Request{Command::kRelocalize, "-12.5 3 90 0.8"}, Request{Command::kMark, ""},
        Request{Command::kMark, "robot stopped at bay 3, unsure why"}}) {
    std::string line = FormatRequest(r);
    ASSERT_EQ(line.back(), '\n');
    line.pop_back();
    std::string error;
    const std::optional<Request> back = ParseRequest(line, &error);
    ASSERT_TRUE(back.has_value()) << error;
    EXPECT_EQ(back->command, r.command);
    EXPECT_EQ(back->argument, r.argument);
  }
  // nc -C sends CRLF.
  EXPECT_TRUE(ParseRequest("status\r", nullptr).has_value());
  // Bytes ≥ 0x80 (UTF-8 file names) pass.
  EXPECT_TRUE(ParseRequest("save-map /maps/Umspannwerk-S\xc3\xbc"
                           "d.map",
                           nullptr)
                  .has_value());
}

TEST(ControlProtocol, MalformedRequestsAreRefusedWithAReason) {
  EXPECT_THAT(Refusal(""), HasSubstr("empty request"));
  EXPECT_THAT(Refusal("STATUS"), HasSubstr("unknown command 'STATUS'"));
  EXPECT_THAT(Refusal("stat"), HasSubstr("unknown command"));
  EXPECT_THAT(Refusal(" status"), HasSubstr("leading space"));
  EXPECT_THAT(Refusal("status "), HasSubstr("trailing space"));
  EXPECT_THAT(Refusal("status now"), HasSubstr("takes no argument"));
  EXPECT_THAT(Refusal("reset 1"), HasSubstr("takes no argument"));
  EXPECT_THAT(Refusal("save-map"), HasSubstr("needs a path"));
  EXPECT_THAT(Refusal("relocalize"), HasSubstr("needs x y yaw_deg"));
  EXPECT_THAT(Refusal("save-map "), HasSubstr("trailing space"));
  EXPECT_THAT(Refusal("save-map map.bin"), HasSubstr("absolute path"));
  EXPECT_THAT(Refusal("save-map  /two/spaces"), HasSubstr("absolute path"));
  EXPECT_THAT(Refusal("save-map /var/lib/swlio/"), HasSubstr("not a directory"));
  EXPECT_THAT(Refusal(std::string("status\0", 7)), HasSubstr("control byte at offset 6"));
  EXPECT_THAT(Refusal("save-map /a\tb"), HasSubstr("control byte"));
  EXPECT_THAT(Refusal("save-map /a\x7f"), HasSubstr("control byte"));
  EXPECT_THAT(Refusal("status\r\r"), HasSubstr("control byte"));
  EXPECT_THAT(Refusal("\xff\xfe"), HasSubstr("unknown command"));
  EXPECT_THAT(Refusal(std::string("save-map /").append(kMaxRequestBytes, 'a')),
              HasSubstr("longer"));
  // An unknown command is echoed only in part, on one line.
  const std::string long_word = Refusal(std::string(1000, 'x'));
  EXPECT_LT(long_word.size(), 200u);
}

TEST(ControlProtocol, ReaderTakesOneLineInPieces) {
  RequestReader r;
  EXPECT_EQ(r.Add("sa"), RequestReader::State::kIncomplete);
  EXPECT_EQ(r.Add(""), RequestReader::State::kIncomplete);
  EXPECT_EQ(r.Add("ve-map /x"), RequestReader::State::kIncomplete);
  EXPECT_EQ(r.Add(".map\n"), RequestReader::State::kComplete);
  EXPECT_EQ(r.line(), "save-map /x.map");
}

TEST(ControlProtocol, ReaderRefusesASecondLineAndOversize) {
  RequestReader two;
  EXPECT_EQ(two.Add("status\nreset\n"), RequestReader::State::kError);
  EXPECT_THAT(two.error(), HasSubstr("one request per connection"));
  RequestReader later;
  EXPECT_EQ(later.Add("status\n"), RequestReader::State::kComplete);
  EXPECT_EQ(later.Add("x"), RequestReader::State::kError);

  RequestReader big;
  const std::string chunk(1000, 'a');
  RequestReader::State s = RequestReader::State::kIncomplete;
  size_t fed = 0;
  while (s == RequestReader::State::kIncomplete && fed < 10 * kMaxRequestBytes) {
    s = big.Add(chunk);
    fed += chunk.size();
  }
  EXPECT_EQ(s, RequestReader::State::kError);
  EXPECT_LE(fed, kMaxRequestBytes + chunk.size());  // refused as soon as it was too long
  EXPECT_LE(big.line().size(), kMaxRequestBytes);
  EXPECT_THAT(big.error(), HasSubstr("longer than 4096"));
  // Exactly at the limit is fine: 4095 bytes and the newline.
  RequestReader edge;
  std::string edge_line(kMaxRequestBytes - 1, 'a');
  edge_line.push_back('\n');
  EXPECT_EQ(edge.Add(edge_line), RequestReader::State::kComplete);
}

TEST(ControlProtocol, RepliesRoundTrip) {
  const Reply ok{ReplyStatus::kOk, "saved 12 nodes", "map: /m\nnodes: 12\n"};
  std::string error;
  std::optional<Reply> back = ParseReply(FormatReply(ok), &error);
  ASSERT_TRUE(back) << error;
  EXPECT_EQ(back->status, ReplyStatus::kOk);
  EXPECT_EQ(back->message, "saved 12 nodes");
  EXPECT_EQ(back->body, ok.body);
  EXPECT_EQ(FormatReply({ReplyStatus::kOk, "", ""}), "ok\n");
  for (ReplyStatus s : {ReplyStatus::kBadRequest, ReplyStatus::kRefused, ReplyStatus::kBusy,
                        ReplyStatus::kFailed, ReplyStatus::kTimeout}) {
    const std::string text = FormatReply({s, "two\nlines", "ignored"});
    EXPECT_EQ(text, std::string("error ").append(ToString(s)).append(": two lines\n"));
    back = ParseReply(text, &error);
    ASSERT_TRUE(back) << error;
    EXPECT_EQ(back->status, s);
    EXPECT_EQ(back->message, "two lines");
  }
}

TEST(ControlProtocol, MalformedRepliesAreRefused) {
  std::string error;
  EXPECT_FALSE(ParseReply("", &error));
  EXPECT_THAT(error, HasSubstr("complete first line"));
  EXPECT_FALSE(ParseReply("ok", &error));  // cut before the newline
  EXPECT_FALSE(ParseReply("okay\n", &error));
  EXPECT_FALSE(ParseReply("error nonsense: x\n", &error));
  EXPECT_FALSE(ParseReply("error refused x\n", &error));
  EXPECT_FALSE(ParseReply("error refused: x\nmore\n", &error));  // errors have no body
}

}  // namespace
}  // namespace swlio::control
