# Installation layout and the Debian package. Everything a running rangefitd reads is generated
# from GNUInstallDirs, so the unit, the sample configuration and the files they name agree for
# any prefix: /usr/local (the default; config in /usr/local/etc/rangefitd) and /usr (a package;
# config in /etc/rangefitd, because GNUInstallDirs maps the /usr prefix's sysconfdir to /etc).
#
#   cmake -S . -B build -DCMAKE_INSTALL_PREFIX=/usr
#   cmake --build build -j2 --target rangefit rangefitd
#   cd build && cpack -G DEB        # rangefit_<version>_amd64.deb
#
# Install components: the programs and the message definitions (share/rangefit/idl and
# share/rangefit/rangefit_msgs, daemon/CMakeLists.txt) are "Unspecified" (CMake's default); unit,
# configuration, data and documents are "files", which installs without a build (the packaging
# test checks a /usr layout that way).

set(RANGEFITD_EXE ${CMAKE_INSTALL_FULL_SBINDIR}/rangefitd)
set(RANGEFITD_CONFDIR ${CMAKE_INSTALL_FULL_SYSCONFDIR}/rangefitd)
set(RANGEFITD_CONFIG ${RANGEFITD_CONFDIR}/rangefitd.toml)
set(RANGEFIT_SHARE_DIR ${CMAKE_INSTALL_DATADIR}/rangefit)
set(RANGEFIT_SCENES_DIR ${CMAKE_INSTALL_FULL_DATADIR}/rangefit/scenes)
set(RANGEFIT_DOC_FILE ${CMAKE_INSTALL_FULL_DOCDIR}/README.md)
# systemd reads units from <prefix>/lib/systemd/system for both /usr and /usr/local (not libdir,
# which is lib/x86_64-linux-gnu on Debian).
set(RANGEFIT_SYSTEMD_UNIT_DIR lib/systemd/system CACHE STRING
    "Directory of the systemd unit, relative to the prefix or absolute")

# Who may talk to rangefitd over IP (the unit's IPAddressAllow=): DDS peers and the clients of
# its [http]/[tcp] interfaces, whose listen addresses must lie in these ranges.
set(RANGEFITD_IP_ADDRESS_ALLOW
    "localhost link-local multicast 10.0.0.0/8 172.16.0.0/12 192.168.0.0/16 fc00::/7"
    CACHE STRING "IPAddressAllow= of the rangefitd unit (systemd.resource-control)")
# rangefitd is built with the same list and refuses a configuration whose [http]/[tcp] listen
# address or DDS interface lies outside it (daemon/service/address_check.hpp): the socket would
# bind and then never see a client.
set_source_files_properties(
  ${PROJECT_SOURCE_DIR}/daemon/service/ip_allow.cpp DIRECTORY ${PROJECT_SOURCE_DIR}/daemon/service
  PROPERTIES COMPILE_DEFINITIONS "RANGEFITD_IP_ADDRESS_ALLOW=\"${RANGEFITD_IP_ADDRESS_ALLOW}\"")
# udev and sysusers read <prefix>/lib/{udev/rules.d,sysusers.d} for both /usr and /usr/local.
set(RANGEFIT_UDEV_RULES_DIR lib/udev/rules.d CACHE STRING
    "Directory of the udev rule giving rangefitd the CSS, relative to the prefix or absolute")
set(RANGEFIT_SYSUSERS_DIR lib/sysusers.d CACHE STRING
    "Directory of rangefitd's sysusers.d file, relative to the prefix or absolute")
set(RANGEFIT_CSS_USB_ID "1d6b:0105" CACHE STRING
    "VID:PID (hex) of the CSS that the udev rule gives to rangefitd (the driver's default)")
set(RANGEFIT_GROUP rangefit)  # owns the CSS's USB device; the service's dynamic user joins it
string(REPLACE ":" ";" css_usb_id "${RANGEFIT_CSS_USB_ID}")
list(GET css_usb_id 0 RANGEFIT_CSS_USB_VID)
list(GET css_usb_id 1 RANGEFIT_CSS_USB_PID)

# What the programs print: the version, and where the installed sample configuration is.
foreach(program rangefit rangefitd)
  if(TARGET ${program})
    target_compile_definitions(${program} PRIVATE RANGEFIT_VERSION="${PROJECT_VERSION}"
                                                  RANGEFITD_CONFIG="${RANGEFITD_CONFIG}")
  endif()
endforeach()

set(generated ${PROJECT_BINARY_DIR}/systemd)
configure_file(${PROJECT_SOURCE_DIR}/systemd/rangefitd.service.in ${generated}/rangefitd.service
               @ONLY)
configure_file(${PROJECT_SOURCE_DIR}/systemd/rangefitd.toml ${generated}/rangefitd.toml @ONLY)
configure_file(${PROJECT_SOURCE_DIR}/systemd/70-rangefitd.rules.in ${generated}/70-rangefitd.rules
               @ONLY)
configure_file(${PROJECT_SOURCE_DIR}/systemd/rangefitd.sysusers.in ${generated}/rangefitd.conf
               @ONLY)

install(FILES ${generated}/rangefitd.service DESTINATION ${RANGEFIT_SYSTEMD_UNIT_DIR}
        COMPONENT files)
install(FILES ${generated}/70-rangefitd.rules DESTINATION ${RANGEFIT_UDEV_RULES_DIR}
        COMPONENT files)
install(FILES ${generated}/rangefitd.conf DESTINATION ${RANGEFIT_SYSUSERS_DIR} COMPONENT files)
install(FILES ${generated}/rangefitd.toml ${PROJECT_SOURCE_DIR}/systemd/cyclonedds.xml
        DESTINATION ${RANGEFITD_CONFDIR} COMPONENT files)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/data/scenes/ DESTINATION ${RANGEFIT_SHARE_DIR}/scenes
        COMPONENT files)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/data/models/ DESTINATION ${RANGEFIT_SHARE_DIR}/models
        COMPONENT files)
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/CONTRIBUTING.md
        DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT files)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs
        COMPONENT files)

# The Debian package: `cpack -G DEB` in the build directory. It installs to the configured
# prefix, so the package holds exactly what the unit names.
set(CPACK_PACKAGE_NAME rangefit)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "rangefit")
set(CPACK_PACKAGE_CONTACT "rangefit maintainers <rangefit@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "part detection by fitting geometric models to laser range scans (rangefitd + rangefit)")
string(CONCAT CPACK_PACKAGE_DESCRIPTION
       "rangefitd runs a robot cell's range sensors as a systemd service, detects bore holes and\n"
       "objects in the fused point clouds and publishes the poses over ROS 2-compatible DDS;\n"
       "rangefit runs the same detectors offline on PLY/PCD files, simulates and replays scans.")
set(CPACK_PACKAGING_INSTALL_PREFIX ${CMAKE_INSTALL_PREFIX})
# The package holds two programs: build them (or everything) first, and cpack (and the install
# target) package what is built instead of building the whole test suite and benchmarks first.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # rangefit_<version>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_HOMEPAGE "file://${RANGEFIT_DOC_FILE}")
# Run-time dependencies from the binaries' shared libraries (dpkg-shlibdeps: Debian packages).
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# dpkg keeps an administrator's edits of these on upgrade and removes them only on purge.
set(conffiles ${PROJECT_BINARY_DIR}/debian/conffiles)
file(WRITE ${conffiles} "${RANGEFITD_CONFIG}\n${RANGEFITD_CONFDIR}/cyclonedds.xml\n")
# Maintainer scripts (what debhelper's sysusers, udev and systemd steps would add): postinst
# creates the group rangefit from the installed sysusers.d file, reloads udev's rules and
# re-triggers USB devices (a CSS already plugged in gets its group), and reloads systemd; prerm
# stops the service on removal; postrm reloads again and removes the spool on purge. Without
# them a fresh install has no group rangefit until the next boot, and the service cannot start.
if(IS_ABSOLUTE ${RANGEFIT_SYSUSERS_DIR})
  set(RANGEFIT_SYSUSERS_FILE ${RANGEFIT_SYSUSERS_DIR}/rangefitd.conf)
else()
  set(RANGEFIT_SYSUSERS_FILE ${CMAKE_INSTALL_PREFIX}/${RANGEFIT_SYSUSERS_DIR}/rangefitd.conf)
endif()
set(maintainer_scripts ${conffiles})
foreach(script postinst prerm postrm)
  configure_file(${PROJECT_SOURCE_DIR}/systemd/rangefitd.${script}.in
                 ${PROJECT_BINARY_DIR}/debian/${script} @ONLY
                 FILE_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE
                                  WORLD_READ WORLD_EXECUTE)
  list(APPEND maintainer_scripts ${PROJECT_BINARY_DIR}/debian/${script})
endforeach()
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${maintainer_scripts})
if(NOT CMAKE_INSTALL_PREFIX STREQUAL "/usr")
  message(STATUS "rangefit: install prefix ${CMAKE_INSTALL_PREFIX}; a Debian package normally "
                 "uses -DCMAKE_INSTALL_PREFIX=/usr (configuration in /etc/rangefitd)")
endif()
include(CPack)
