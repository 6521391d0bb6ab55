#!/usr/bin/python3
"""Writes a swliod configuration for a live simulator run: the rig (LiDAR-IMU extrinsic) from
the simulator's manifest.yaml, the ports and pty it streams to, DDS on the loopback-only XML,
logs into WORK/log; everything else the defaults of config/swlio.yaml's keys.

Usage: scripts/sim_daemon_config.py WORK ROOT MSOP_PORT DIFOP_PORT [STATUS_PERIOD_S]
                                    [--loop-closure | --no-loop-closure]
  reads WORK/sim/manifest.yaml, writes WORK/swlio.yaml (the pty is WORK/imu.pty);
  estimator.loop_closure.enabled is true (the default) unless --no-loop-closure.
Used by scripts/demo and scripts/soak."""
import re
import sys

args = [a for a in sys.argv[1:] if a not in ("--loop-closure", "--no-loop-closure")]
loop_closure = "false" if "--no-loop-closure" in sys.argv[1:] else "true"
work, root, msop, difop = args[0:4]
status_period_s = args[4] if len(args) > 4 else "5.0"
m = open(f"{work}/sim/manifest.yaml").read()
# Version 2: the extrinsic is in the drivers' LiDAR frame (x forward, y left, z up), as swliod
# reads it; an older simulator's manifest would give a wrong rig (drivers/recording_format.h).
if re.search(r"^format_version: 2$", m, re.M) is None:
    sys.exit(f"{work}/sim/manifest.yaml: not format_version 2; rerun it with this swlio-sim")
t = re.search(r"extrinsic_T_imu_lidar:.*?translation_m: \[([^\]]*)\]", m, re.S).group(1)
r = re.search(r"rotation_rpy_deg: \[([^\]]*)\]", m).group(1)
open(f"{work}/swlio.yaml", "w").write(f"""config_version: 1
lidar:
  model: rs16
  bind_address: 127.0.0.1
  msop_port: {msop}
  difop_port: {difop}
imu:
  device: {work}/imu.pty
  configure_on_start: false   # the simulator streams without the configuration handshake
estimator:
  extrinsic_imu_lidar:
    translation_m: [{t}]
    rotation_rpy_deg: [{r}]
  loop_closure:
    enabled: {loop_closure}
ipc:
  dds_config_file: {root}/config/cyclonedds-loopback.xml
  stamp_clock: monotonic   # the simulator's ground truth is on CLOCK_MONOTONIC
logging:
  directory: {work}/log
  stderr_level: warn
  status_period_s: {status_period_s}
""")
