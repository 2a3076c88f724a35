# Install layout of the xregulator package (issue 10). Included from
# tools/CMakeLists.txt. Paths follow Debian: /usr/sbin, /usr/libexec,
# /etc/xregulator, /usr/share/xregulator/www, /lib/systemd/system.
include(GNUInstallDirs)

set(XR_SYSTEMD_UNITDIR "/lib/systemd/system" CACHE PATH "Where the systemd unit is installed")

install(FILES ${XR_ROOT}/config/xregulator.toml DESTINATION ${CMAKE_INSTALL_FULL_SYSCONFDIR}/xregulator)
if(EXISTS ${XR_ROOT}/web/www)
  install(DIRECTORY ${XR_ROOT}/web/www/ DESTINATION ${CMAKE_INSTALL_DATADIR}/xregulator/www
          PATTERN ".gitignore" EXCLUDE PATTERN ".gitkeep" EXCLUDE)
else()
  install(DIRECTORY DESTINATION ${CMAKE_INSTALL_DATADIR}/xregulator/www)
endif()
install(FILES ${XR_ROOT}/systemd/xregulatord.service DESTINATION ${XR_SYSTEMD_UNITDIR})

# The daemon target is defined by daemon/app, which CMake reads after this
# file; install it once the whole tree has been read.
function(xr_install_daemon)
  if(TARGET xregulatord)
    install(TARGETS xregulatord RUNTIME DESTINATION ${CMAKE_INSTALL_SBINDIR})
  else()
    message(STATUS "xregulatord target not defined yet: the install has no daemon")
  endif()
endfunction()
cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR} CALL xr_install_daemon)
