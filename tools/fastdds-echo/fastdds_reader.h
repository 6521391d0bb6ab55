#pragma once
/// @file
/// A Fast DDS reader of one topic with the QoS a ROS 2 subscription asks for, and the function
/// that takes its samples one by one and hands each to a handler (print, or the TF check).

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace swlio::tools::fastdds_echo {

/// RELIABLE always (every swlio writer is reliable); the rest as the ROS 2 subscription:
/// ROS 2's default (VOLATILE, KEEP_LAST 10), a latched map display (TRANSIENT_LOCAL, 1), tf2's
/// listener on /tf (VOLATILE, 100) and /tf_static (TRANSIENT_LOCAL, 1).
struct ReaderQos {
  bool transient_local = false;
  int depth = 10;
};

/// A reader and the function that takes one sample from it.
struct Reader {
  eprosima::fastdds::dds::DataReader* reader = nullptr;
  std::function<bool()> take;  // false when nothing was left to take
};

/// Adds a reader of `topic_name` to `readers` whose samples go to `handle`; appends
/// " <topic>=<type name>" to `ready`. False when Fast DDS refuses an entity.
template <typename PubSubType>
bool AddReader(eprosima::fastdds::dds::DomainParticipant* participant,
               eprosima::fastdds::dds::Subscriber* subscriber,
               const std::string& topic_name,
               const ReaderQos& reader_qos,
               std::function<void(const typename PubSubType::type&)> handle,
               std::vector<Reader>* readers,
               std::string* ready) {
  namespace fdds = eprosima::fastdds::dds;
  using Message = typename PubSubType::type;
  fdds::TypeSupport type(new PubSubType());
  if (type.register_type(participant) != ReturnCode_t::RETCODE_OK) return false;
  fdds::Topic* topic =
      participant->create_topic(topic_name, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  if (topic == nullptr) return false;
  fdds::DataReaderQos qos = fdds::DATAREADER_QOS_DEFAULT;
  qos.reliability().kind = fdds::RELIABLE_RELIABILITY_QOS;
  qos.durability().kind = reader_qos.transient_local ? fdds::TRANSIENT_LOCAL_DURABILITY_QOS
                                                     : fdds::VOLATILE_DURABILITY_QOS;
  qos.history().kind = fdds::KEEP_LAST_HISTORY_QOS;
  qos.history().depth = reader_qos.depth;
  fdds::DataReader* reader = subscriber->create_datareader(topic, qos);
  if (reader == nullptr) return false;
  auto sample = std::make_shared<Message>();
  readers->push_back({reader, [reader, sample, handle = std::move(handle)] {
                        fdds::SampleInfo info;
                        if (reader->take_next_sample(sample.get(), &info) !=
                            ReturnCode_t::RETCODE_OK) {
                          return false;
                        }
                        if (info.valid_data) handle(*sample);
                        return true;
                      }});
  ready->append(" ").append(topic_name).append("=").append(type.get_type_name());
  return true;
}

}  // namespace swlio::tools::fastdds_echo
