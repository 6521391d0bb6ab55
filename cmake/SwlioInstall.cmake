# `cmake --install` layout (included from the root CMakeLists.txt after every target exists):
#   <prefix>/bin/                        swliod and the command-line tools
#   <prefix>/share/man/man{1,8}/         their man pages (docs/man/, cmake/SwlioManPages.cmake)
#   <prefix>/share/swlio/report/         swlio-report's Python package (the script is in bin/)
#   <prefix>/lib/systemd/system/         swliod.service (paths of this install filled in)
#   <prefix>/lib/sysusers.d/swlio.conf   the swlio system user (systemd-sysusers)
#   <prefix>/lib/tmpfiles.d/swlio.conf   /run/swlio for the control socket (systemd-tmpfiles)
#   <prefix>/share/swlio/                swliod-realtime.conf, an opt-in drop-in
#   <sysconfdir>/swlio/                  swlio.yaml and the DDS XML files it names
# sysconfdir follows GNUInstallDirs: /etc for prefix /usr, /etc/opt/... for /opt/..., else
# <prefix>/etc. It and the unit's paths are computed at install time (cmake/SwlioInstallFiles.cmake)
# so that `cmake --install build --prefix /usr` lays out a consistent tree whatever prefix the
# build was configured with. systemd units go to lib/, not to the multiarch libdir.
include(GNUInstallDirs)

foreach(_program swliod swlioctl swlio-replay swlio-bag swlio-decode swlio-echo swlio-eval
                 swlio-run swlio-sim)
  if(TARGET ${_program})
    install(TARGETS ${_program} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  endif()
endforeach()
# Programs that are scripts, installed when their source exists: swlio-report (Python 3,
# tools/report/, issue 35). cmake/SwlioPackage.cmake adds python3 to Depends for it.
set(SWLIO_INSTALLED_SCRIPTS)
if(EXISTS ${CMAKE_SOURCE_DIR}/tools/report/swlio-report)
  install(PROGRAMS tools/report/swlio-report DESTINATION ${CMAKE_INSTALL_BINDIR})
  list(APPEND SWLIO_INSTALLED_SCRIPTS swlio-report)
endif()
include(${CMAKE_CURRENT_LIST_DIR}/SwlioManPages.cmake)
install(PROGRAMS tools/report/swlio-report DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY tools/report/swlio_report DESTINATION ${CMAKE_INSTALL_DATADIR}/swlio/report
        FILES_MATCHING PATTERN "*.py" PATTERN "__pycache__" EXCLUDE)
install(FILES systemd/swlio.sysusers.conf DESTINATION lib/sysusers.d RENAME swlio.conf)
install(FILES systemd/swlio.tmpfiles.conf DESTINATION lib/tmpfiles.d RENAME swlio.conf)
install(FILES systemd/swliod-realtime.conf DESTINATION ${CMAKE_INSTALL_DATADIR}/swlio)
install(CODE "
  set(SWLIO_SOURCE_DIR \"${CMAKE_SOURCE_DIR}\")
  set(SWLIO_STAGING_DIR \"${CMAKE_BINARY_DIR}/install-staging\")
  set(SWLIO_BINDIR_REL \"${CMAKE_INSTALL_BINDIR}\")
  set(SWLIO_SYSCONFDIR_CONFIGURED \"${CMAKE_INSTALL_SYSCONFDIR}\")
  include(\"${CMAKE_SOURCE_DIR}/cmake/SwlioInstallFiles.cmake\")")
