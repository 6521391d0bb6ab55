#pragma once
/// @file
/// A small streaming JSON writer for swlio-decode summaries (one object, keys in insertion
/// order, no dependencies). Usage: `JsonWriter j(os); j.BeginObject(); j.Key("n").Value(3);
/// j.EndObject();`. Doubles are written exactly (shortest round trip); NaN/inf as null.

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <ostream>
#include <span>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <vector>

namespace swlio::tools {

class JsonWriter {
 public:
  explicit JsonWriter(std::ostream& os) : os_(os) {}

  JsonWriter& BeginObject() { return Open('{'); }
  JsonWriter& EndObject() { return Close('}'); }
  JsonWriter& BeginArray() { return Open('['); }
  JsonWriter& EndArray() { return Close(']'); }

  JsonWriter& Key(std::string_view key) {
    Separate();
    WriteString(key);
    os_ << ':';
    after_key_ = true;
    return *this;
  }
  JsonWriter& Value(std::string_view v) {
    Separate();
    WriteString(v);
    return *this;
  }
  JsonWriter& Value(const char* v) { return Value(std::string_view(v)); }
  JsonWriter& Value(bool v) {
    Separate();
    os_ << (v ? "true" : "false");
    return *this;
  }
  /// The shortest text that reads back as the same double (std::to_chars); null if not finite.
  JsonWriter& Value(double v) {
    Separate();
    std::array<char, 32> buffer{};
    const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
    if (std::isfinite(v) && ec == std::errc()) {
      os_.write(buffer.data(), end - buffer.data());
    } else {
      os_ << "null";
    }
    return *this;
  }
  template <typename T>
  requires std::is_integral_v<T> &&(!std::is_same_v<T, bool>)JsonWriter& Value(T v) {
    Separate();
    os_ << +v;  // promotes uint8_t to a number
    return *this;
  }
  /// An array of numbers.
  template <typename T>
  JsonWriter& Array(std::span<const T> values) {
    BeginArray();
    for (const T& v : values) Value(v);
    return EndArray();
  }
  template <typename T>
  JsonWriter& Array(const std::vector<T>& values) {
    return Array(std::span<const T>(values));
  }

 private:
  JsonWriter& Open(char c) {
    Separate();
    os_ << c;
    first_.push_back(true);
    return *this;
  }
  JsonWriter& Close(char c) {
    os_ << c;
    if (!first_.empty()) first_.pop_back();
    return *this;
  }
  void Separate() {
    if (after_key_) {
      after_key_ = false;
      return;
    }
    if (!first_.empty()) {
      if (!first_.back()) os_ << ',';
      first_.back() = false;
    }
  }
  void WriteString(std::string_view s) {
    os_ << '"';
    for (const char ch : s) {
      const auto c = static_cast<unsigned char>(ch);
      if (c == '"' || c == '\\') {
        os_ << '\\' << ch;
      } else if (c < 0x20) {
        static constexpr char kHex[] = "0123456789abcdef";
        os_ << "\\u00" << kHex[c >> 4] << kHex[c & 0xF];
      } else {
        os_ << ch;
      }
    }
    os_ << '"';
  }

  std::ostream& os_;
  std::vector<bool> first_;  ///< per open container: nothing written in it yet
  bool after_key_ = false;
};

}  // namespace swlio::tools
