# Read by CTest after the GoogleTest discovery files (tests/CMakeLists.txt): adds to each
# discovered test the labels that scripts/test's sanitizer phases select on. Patterns are
# regular expressions on the full test name, "<module>.<Suite>.<Case>".
#
#   release_only  runs in the Release phase only: whole drives or long checks that take minutes
#                 under ASan and repeat code that shorter tests run there too.
#   no_tsan       left out of the TSan phase: nothing threaded to check, or a peer that trips
#                 TSan inside uninstrumented libraries.

set(_swlio_release_only
  # Drives through the estimator that repeat the shorter drives kept under ASan: the online
  # calibration run, the LiDAR-only drive.
  "\\.OnlineCalibrationRecoversTheExtrinsic"
  "\\.LidarOnlyFollowsTheSimulatedDrive"
  # Two windows over 40 s of ray-cast `aggressive` with unknown time offsets (12 s in Release);
  # the offset estimator itself runs under ASan in TimeOffsetEstimator.* and TimeOffsetDrive.*.
  "\\.TimeOffsetWindow\\."
  # swlio-run twice over 40 s of `aggressive` (one with its IMU receive times delayed).
  "\\.RunTimeOffset\\."
  # swlio-run drives that repeat the window estimator under other options (55, 29, 15 and
  # 64 s under ASan); TightlyCoupledFollowsTheSimulatedDrive and loop closure's tests stay.
  "\\.RunOnShortDrive\\.(TightlyCoupledStartsWhileMoving|ExtrinsicCalibrationRefusesAStraightDrive)"
  "\\.RunOnShortDrive\\.(ConfigWindowSectionAppliesAndFlagsOverride|LoopClosureWritesItsOutputsAndLeavesAStraightDriveAlone)"
  # The deterministic-replay check (34 s under ASan; RecordingReader's own tests stay).
  "\\.ReplayCommand\\.DeterministicReplay"
  # Live fault drives that send well-formed data on another schedule (loss, outages, gaps,
  # clock steps, silence); the faults with malformed or odd content stay under ASan.
  "\\.RuntimeFaults\\.(BurstyUdpLoss|TwoSecond|ImuGap|SerialUnplug|LidarClockJump|ImuCounterWrap)"
  "\\.RuntimeFaults\\.(MissingDifop|LidarThatNever|ImuThatNever)"
  # The Fast DDS consumer's TF check: a whole minute of the short drive with loop closure.
  "\\.RuntimeFastDdsTf\\."
  # The black box on a 42 s live drive with three faults, its incidents replayed; the ring, the
  # incidents and a full disk run under the sanitizers in RecorderRing.* and IncidentStore.*.
  "\\.RuntimeBlackBox\\."
  # Two live drives (a map, then pose hints in it); the localization thread's hints run under
  # the sanitizers in LocalizationThread.*.
  "\\.RuntimeInitialPose\\."
  # Timing checks whose cost under ASan is ray casting a simulated recording (40–60 s each);
  # the clock models, recording writer and reader run under ASan in their own tests.
  "\\.ClockMapping\\.SimulatedClocksAt100Ppm"
  "\\.SimClock\\.LidarHeaderTime"
  "\\.SimRecording\\.SameNameAndSeedGiveIdenticalBytes"
  # MapLocalizer cases that verify dozens of relocalization hypotheses (3–12 s each in Release);
  # the relocalization, look-alike bay and lost-pose cases stay.
  "\\.MapLocalizer\\.(NeverLocalizesInTheMapOfAnotherPlace|WaitsWhereEveryPlaceHasALookAlike)"
  "\\.MapLocalizer\\.(KeepsTrackingWhereTheSceneChanged|ThrottlesRelocalizationWhileAmbiguous)"
  # Moving objects out of the maps: 25 s of `short` ray cast with injected movers (10 s in
  # Release); VisibilityImage.* runs the same tests on hand-made sweeps under the sanitizers.
  "\\.LoopClosureVisibility\\."
  # Three drives, each exported to a bag and run four times; the bag readers, the bag input
  # and the real bag's LiDAR-only run stay under ASan.
  "/BagInputOnDrive\\."
  # A bag run twice for identical output (93 s under ASan); the bag readers stay.
  "\\.BagInputCommand\\.DeterministicReplayOfABagMatchesSwlioRun"
  # swlio-run with the wheel factor (4 s in Release, 70 s under ASan); WheelOdom* units stay.
  "\\.RunOnShortDrive\\.WheelOdometryFactorOnEverySweep"
  # Recovery drives (17–63 s each under ASan): the estimator on one thread over a simulated
  # drive with an outage, a gap or a fault, with and without the checks; DivergenceMonitor.*
  # and the window's own tests stay.
  "\\.RecoveryOnShortDrive\\."
  # Both replay tools over a scaled recording (26 s under ASan); RecordingReader.* stays.
  "\\.ReplayCommand\\.BothToolsWriteAScaledRecordingOnHostTime"
  # The simulator's actors in labelled scans and recordings, over laps (8–16 s each);
  # SimActors.LidarSeesThemWhereTheyAre keeps their ray casting under ASan.
  "\\.SimActors\\.(LabelledScansMarkMovingPoints|RecordingWritesActorsCsv|ActorsRepeatWithTheLaps)"
  # Relocalization among look-alikes and after a lost pose (20–22 s each);
  # MapLocalizer.RelocalizesWithoutAGuessAndTracks stays.
  "\\.MapLocalizer\\.(NeverLocalizesAtALookAlikeBay|FindsALostPoseAgain)"
  "\\.MapLocalizer\\.NeverLocalizesAtALookAlikeWhereATruckWasParked"
  # Live drives with well-formed data on another schedule or clock, or with commands (44–58 s
  # each under ASan); Runtime.TracksASimulatedDrive stays, RuntimeControl.* runs under TSan.
  "\\.Runtime\\.AWallClockStepMovesTheStampsOnly"
  "\\.RuntimeFaults\\.ASerialStall"
  "\\.RuntimeControl\\.StatusSaveMapAndResetOnALiveDrive"
  # The simulator's actors against the world over a whole drive (2 s in Release, 39 s here).
  "\\.SimActors\\.NeverThroughTheWorld"
  # Laps of loop closure (24–30 s each under ASan); WithoutPlacesTheStoreGrowsEveryLap stays.
  "\\.LoopClosureLaps\\.(KeyframeStoreStopsGrowing|MergedCloudFromTheStore)"
  # DDS Security's cryptography runs in uninstrumented plugins; OnlyAGrantedIdentityReadsThePose
  # keeps our side of it under ASan.
  "\\.DdsSecurity\\.OnlyAGrantedIdentityPublishesInitialPose")

set(_swlio_no_tsan
  # The Fast DDS subscriber (a test tool) trips TSan inside Fast DDS's timed mutexes, which live
  # in the uninstrumented libstdc++; the interop test runs in the other two phases.
  "\\.FastDdsInterop"
  "\\.RuntimeFastDdsTf\\."
  # DDS Security: the handshake and every sample's cryptography run in Debian's uninstrumented
  # security plugins and OpenSSL (libcrypto's locks are invisible to TSan); our side of it is the
  # XML and the participant, which Runtime.* and IpcRoundTrip.* run under TSan.
  "\\.DdsSecurity\\."
  "\\.RuntimeInitialPose\\."
  # The estimator or a simulated recording on one thread: nothing for TSan, minutes under it.
  "\\.RecoveryOnShortDrive\\."
  "\\.ClockMapping\\."
  "\\.RecordingReaderStreams\\."
  # Live drives with injected faults run the same threads as Runtime.*, which stays.
  "\\.RuntimeFaults\\."
  "\\.RuntimeBlackBox\\."
  # A clock step is the stamp clock's arithmetic on the same threads as Runtime.TracksASimulated-
  # Drive (61 s under TSan); RuntimeControl.* keeps a second live drive under TSan.
  "\\.Runtime\\.AWallClockStepMovesTheStampsOnly"
  # The bag file readers read on the calling thread (103 s under TSan for a cut loop in SQLite).
  "\\.Rosbag2SqliteReader\\.")

foreach(_swlio_list IN ITEMS core drivers estimator ipc daemon daemon_live tools)
  foreach(_test IN LISTS swlio_${_swlio_list}_TESTS)
    string(REGEX MATCH "^[a-z]+" _labels "${_test}")
    foreach(_label IN ITEMS release_only no_tsan)
      foreach(_pattern IN LISTS _swlio_${_label})
        if(_test MATCHES "${_pattern}")
          list(APPEND _labels ${_label})
          break()
        endif()
      endforeach()
    endforeach()
    list(LENGTH _labels _count)
    if(_count GREATER 1)
      set_tests_properties("${_test}" PROPERTIES LABELS "${_labels}")
    endif()
  endforeach()
endforeach()
