# Install layout of the xregulator package. Included from
# tools/CMakeLists.txt. Paths follow Debian: /usr/libexec,
# /etc/xregulator, /lib/systemd/system.
include(GNUInstallDirs)

set(XR_SYSTEMD_UNITDIR "/lib/systemd/system" CACHE PATH "Where the systemd unit is installed")

install(FILES ${XR_ROOT}/config/xregulator.toml DESTINATION ${CMAKE_INSTALL_FULL_SYSCONFDIR}/xregulator)
# Dashboard assets (/usr/share/xregulator/www) are installed by web/CMakeLists.txt.
install(FILES ${XR_ROOT}/systemd/xregulatord.service DESTINATION ${XR_SYSTEMD_UNITDIR})

# /usr/sbin/xregulatord is installed by daemon/app/CMakeLists.txt.
