# `cpack -G DEB` in the build tree: the Debian package swlio_<version>-<release>_<arch>.deb of
# what `cmake --install build --prefix /usr` lays out (cmake/SwlioInstall.cmake), plus the
# maintainer scripts, conffiles list, copyright and changelog in packaging/deb/. Included from
# the root CMakeLists.txt after cmake/SwlioInstall.cmake. Building and checking it:
# docs/packaging.md.

# The Debian revision (Debian Policy 5.6.12: [epoch:]upstream_version-debian_revision); the
# upstream version is project()'s. `cpack -D CPACK_DEBIAN_PACKAGE_RELEASE=N` overrides it for
# one package (scripts/package-check builds its upgrade that way).
set(SWLIO_PACKAGE_RELEASE 1 CACHE STRING "Debian revision of the swlio package")
set(SWLIO_PACKAGE_MAINTAINER
    "swlio maintainers <maintainers@users.noreply.h-seed-7bf02788.example>"
    CACHE STRING "Maintainer field of the swlio package")
set(_deb ${CMAKE_SOURCE_DIR}/packaging/deb)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME swlio)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_DEBIAN_PACKAGE_RELEASE ${SWLIO_PACKAGE_RELEASE})
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # <name>_<version>-<release>_<arch>.deb
set(CPACK_PACKAGE_CONTACT ${SWLIO_PACKAGE_MAINTAINER})
set(CPACK_DEBIAN_PACKAGE_MAINTAINER ${SWLIO_PACKAGE_MAINTAINER})
set(CPACK_DEBIAN_PACKAGE_SECTION misc)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "LiDAR-inertial localization daemon for inspection robots")
set(CPACK_PACKAGE_DESCRIPTION [=[
swliod reads RoboSense RS-LiDAR-16 UDP packets and Xsens MTi serial frames
(and wheel odometry over SocketCAN), runs a tightly coupled LiDAR-inertial
estimator with loop closure and publishes pose, odometry and transforms over
Cyclone DDS with ROS 2 type and topic names.

The package holds the daemon, its systemd unit (installed disabled: enable it
once /etc/swlio/swlio.yaml fits the robot), the swlio system user, and the
command-line tools swlioctl, swlio-replay, swlio-bag, swlio-decode,
swlio-echo, swlio-eval, swlio-run and swlio-sim.]=])

# Runtime libraries from dpkg-shlibdeps on the installed programs, and the programs the
# maintainer scripts and the unit need: systemd (systemd-sysusers, systemd-tmpfiles, and the
# Type=notify unit with its watchdog). swlio-report, when packaged, is a Python 3 script.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(_depends "systemd")
if("swlio-report" IN_LIST SWLIO_INSTALLED_SCRIPTS)
  string(APPEND _depends ", python3, python3-yaml")
endif()
set(CPACK_DEBIAN_PACKAGE_DEPENDS ${_depends})

# Install as `cmake --install --prefix /usr` with DESTDIR set, so that the unit's ExecStart and
# the config directory are the final paths (/usr/bin/swliod, /etc/swlio), not the staging tree.
# (With CPACK_SET_DESTDIR, CPack installs with CMAKE_INSTALL_PREFIX = CPACK_INSTALL_PREFIX.)
set(CPACK_SET_DESTDIR ON)
set(CPACK_INSTALL_PREFIX /usr)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_COMPRESSION_TYPE xz)

# The config files dpkg keeps when the operator changed them (Debian Policy 10.7.3, deb-conffiles(5)):
# every file under /etc/swlio (cmake/SwlioInstallFiles.cmake installs them).
set(_conffiles "/etc/swlio/swlio.yaml\n")
foreach(_xml cyclonedds-loopback.xml fastdds-loopback.xml)
  if(EXISTS ${CMAKE_SOURCE_DIR}/config/${_xml})
    string(APPEND _conffiles "/etc/swlio/${_xml}\n")
  endif()
endforeach()
file(WRITE ${CMAKE_BINARY_DIR}/deb/conffiles ${_conffiles})
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
    ${CMAKE_BINARY_DIR}/deb/conffiles ${_deb}/postinst ${_deb}/prerm ${_deb}/postrm)
# Control files get 0644, scripts 0755 whatever the checkout's modes (lintian
# control-file-has-bad-permissions).
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)

# /usr/share/doc/swlio: copyright (DEP-5) and changelog.Debian.gz (Debian Policy 12.5, 12.7;
# gzip -9n as for the man pages).
set(_changelog_gz ${CMAKE_BINARY_DIR}/deb/changelog.Debian.gz)
add_custom_command(OUTPUT ${_changelog_gz}
  COMMAND gzip -9n -c ${_deb}/changelog > ${_changelog_gz}
  DEPENDS ${_deb}/changelog VERBATIM)
add_custom_target(swlio-deb-docs ALL DEPENDS ${_changelog_gz})
install(FILES ${_deb}/copyright ${_changelog_gz} DESTINATION ${CMAKE_INSTALL_DOCDIR})

# Tags that do not apply to this package, each with its reason (lintian's overrides directory).
install(FILES ${_deb}/lintian-overrides DESTINATION ${CMAKE_INSTALL_DATADIR}/lintian/overrides
        RENAME swlio)

include(CPack)
