# Install layout of the xregulator package. Included from
# tools/CMakeLists.txt. Paths follow Debian: /usr/libexec,
# /etc/xregulator, /lib/systemd/system.
include(GNUInstallDirs)

set(XR_SYSTEMD_UNITDIR "/lib/systemd/system" CACHE PATH "Where the systemd unit is installed")

install(FILES ${XR_ROOT}/config/xregulator.toml DESTINATION ${CMAKE_INSTALL_FULL_SYSCONFDIR}/xregulator)
# Dashboard assets (/usr/share/xregulator/www) are installed by web/CMakeLists.txt.
install(FILES ${XR_ROOT}/systemd/xregulatord.service DESTINATION ${XR_SYSTEMD_UNITDIR})

# /usr/sbin/xregulatord is installed by daemon/app/CMakeLists.txt.

# Updates (docs/operations.md "Updates and the way back"): the gate apt runs
# before dpkg, the post-update health check and rollback, the release record
# the postinst writes, and unattended-upgrades' origin (off until turned on).
install(PROGRAMS ${XR_ROOT}/tools/update/xregulator-update-gate ${XR_ROOT}/tools/update/xregulator-update-check
                 ${XR_ROOT}/tools/update/xregulator-update-record
        DESTINATION ${CMAKE_INSTALL_LIBEXECDIR}/xregulator)
install(FILES ${XR_ROOT}/tools/update/51xregulator-update-gate ${XR_ROOT}/tools/update/52xregulator-unattended-upgrades
        DESTINATION ${CMAKE_INSTALL_FULL_SYSCONFDIR}/apt/apt.conf.d)
install(FILES ${XR_ROOT}/systemd/xregulator-update-check.service DESTINATION ${XR_SYSTEMD_UNITDIR})
