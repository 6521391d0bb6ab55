// Small shared pieces of the bag reader interface (bag_reader.h).

#include "swlio/drivers/bag/bag_reader.h"

namespace swlio::drivers::bag {

MessageEncoding EncodingFromName(std::string_view name) {
  if (name == "cdr") return MessageEncoding::kCdr;
  if (name == "ros1") return MessageEncoding::kRos1;
  return MessageEncoding::kUnknown;
}

}  // namespace swlio::drivers::bag
