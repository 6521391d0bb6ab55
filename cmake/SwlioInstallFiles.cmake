# Runs inside `cmake --install` (see cmake/SwlioInstall.cmake): CMAKE_INSTALL_PREFIX is the
# prefix of this install (--prefix wins over the configured one); file(INSTALL) adds $DESTDIR.

if(IS_ABSOLUTE "${SWLIO_SYSCONFDIR_CONFIGURED}")
  set(_sysconfdir "${SWLIO_SYSCONFDIR_CONFIGURED}")
elseif(CMAKE_INSTALL_PREFIX STREQUAL "/usr")
  set(_sysconfdir "/etc")
elseif(CMAKE_INSTALL_PREFIX MATCHES "^/opt/")
  set(_sysconfdir "/etc${CMAKE_INSTALL_PREFIX}")
else()
  set(_sysconfdir "${CMAKE_INSTALL_PREFIX}/${SWLIO_SYSCONFDIR_CONFIGURED}")
endif()
set(SWLIO_BINDIR "${CMAKE_INSTALL_PREFIX}/${SWLIO_BINDIR_REL}")
set(SWLIO_SYSCONFDIR "${_sysconfdir}")

configure_file("${SWLIO_SOURCE_DIR}/systemd/swliod.service.in"
               "${SWLIO_STAGING_DIR}/swliod.service" @ONLY)
file(INSTALL "${SWLIO_STAGING_DIR}/swliod.service"
     DESTINATION "${CMAKE_INSTALL_PREFIX}/lib/systemd/system")

# swlio.yaml names its DDS XML relative to its own directory, so the XML files go beside it.
set(_config_files "${SWLIO_SOURCE_DIR}/config/swlio.yaml")
foreach(_xml cyclonedds-loopback.xml fastdds-loopback.xml)
  if(EXISTS "${SWLIO_SOURCE_DIR}/config/${_xml}")
    list(APPEND _config_files "${SWLIO_SOURCE_DIR}/config/${_xml}")
  endif()
endforeach()
file(INSTALL ${_config_files} DESTINATION "${SWLIO_SYSCONFDIR}/swlio")
