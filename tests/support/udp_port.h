#pragma once
/// @file
/// UDP ports for the tests' receivers that nothing else on the machine sends to.
///
/// A receiver bound to port 0 gets a port from the kernel's ephemeral range (32768–60999 on
/// Debian), and that range holds the ports of the DDS domains the tests use: Cyclone DDS (and
/// Fast DDS) put domain d at 7400 + 250·d, and with unicast discovery over loopback every
/// participant of the domain sends its SPDP datagrams to the even ports 7410..7510 of that band
/// (one per possible participant index; ../../config/cyclonedds-loopback.xml allows 50). Measured
/// here: one swlio-echo in domain 140 sent 3 datagrams in 3 s to each of 42410, 42420 and 42430.
/// A CI run's daemon test got 14 of them on its LiDAR port, counted as bad packets.

#include <cstdint>

namespace swlio::test {

/// A port on 127.0.0.1 that was free a moment ago, below the ephemeral range (no other program
/// gets it by binding port 0) and outside every domain's DDS band. Never the same port twice in
/// one process; random across processes, so tests run in parallel do not pick the same one.
uint16_t QuietUdpPort();

}  // namespace swlio::test
