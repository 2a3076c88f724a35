# xregulator — one command each: `make run`, `make test`.
# deps installs every Debian 12 package the build, `make run` and the tests
# need, deps-tools what the benchmarks, packaging and plots add; both are
# idempotent and only call apt-get when something is missing.

BUILD   ?= build
JOBS    ?= $(shell nproc)
CONFIG  ?= config/xregulator.toml
STATE   ?= var/xregulator.db
HTTP    ?= 127.0.0.1:8080

DEB_PACKAGES := build-essential cmake pkg-config ninja-build \
  libboost1.81-dev libboost-json1.81-dev \
  libgpiod-dev gpiod libsqlite3-dev sqlite3 libssl-dev \
  libspdlog-dev libfmt-dev libtomlplusplus-dev \
  libgtest-dev libgmock-dev googletest \
  libsystemd-dev systemd \
  mosquitto mosquitto-clients libmosquitto-dev \
  chromium curl python3 clang libclang-rt-14-dev clang-format \
  dbus python3-dbus python3-gi gnupg
# What only packaging, the update test, the benchmarks and the plots need
# (deps-tools): not installed by `make test` and `make run`, which saves a
# fresh machine's first `make test` the download and unpacking of these.
TOOL_PACKAGES := libbenchmark-dev wrk valgrind python3-matplotlib graphviz \
  debhelper devscripts lintian fakeroot dpkg-dev \
  reprepro unattended-upgrades

.PHONY: all deps build run test bench deb clean format deps-cross test-arm64 scenarios dashboard-screenshots soak

all: build

# apt-get update, tried three times: a Debian mirror in the middle of a sync answers
# "File has unexpected size" for a minute or two. If it still fails, the install
# goes on with the indexes there are, and fails itself if a package cannot be had.
APT_UPDATE = for try in 1 2 3; do $$SUDO apt-get update && break; \
  echo "apt-get update failed (try $$try of 3; a mirror may be syncing)"; [ $$try = 3 ] || sleep 30; done

# APT_INSTALL(list, label): installs the packages of the list not yet installed.
APT_INSTALL = missing=""; \
	for p in $(1); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "ok installed" || missing="$$missing $$p"; \
	done; \
	if [ "$(2)" = deps ] && { ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; }; then missing="$$missing nodejs npm"; fi; \
	if [ -n "$$missing" ]; then \
	  echo "$(2): installing$$missing"; \
	  SUDO=""; [ "$$(id -u)" = 0 ] || SUDO=sudo; \
	  $(APT_UPDATE); DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y --no-install-recommends $$missing; \
	else echo "$(2): all present"; fi

deps:
	@$(call APT_INSTALL,$(DEB_PACKAGES),deps)
	@if [ -f web/package.json ]; then $(MAKE) --no-print-directory -C web deps; fi
	@$(MAKE) --no-print-directory -C tests/integrations/signalk deps
	@$(MAKE) --no-print-directory -C tests/integrations/n2k deps

.PHONY: deps-tools
deps-tools: deps
	@$(call APT_INSTALL,$(TOOL_PACKAGES),deps-tools)

# The development tree builds what the tests need; the benchmarks have their
# own optimised tree (make bench, below), so they are not linked here too.
# It is built for build time, not for speed: no link-time optimisation and
# -g1 (line tables and function names, enough for a backtrace) took 43 % less
# CPU for a cold build than LTO with full debug information; the daemon runs
# the simulations about 25 % slower without LTO, which costs the tests far
# less than it saves (docs/development.md "make test's time"). The Debian
# package keeps LTO (CMakeLists.txt's default).
DEV_FLAGS := -DCMAKE_BUILD_TYPE=RelWithDebInfo -DXR_BUILD_BENCH=OFF -DXR_LTO=OFF \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG"
$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -G Ninja $(DEV_FLAGS)

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

run: build
	@mkdir -p $(dir $(STATE))
	$(BUILD)/daemon/app/xregulatord --sim --speed 1 --config $(CONFIG) --state-db $(STATE) --http $(HTTP)

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS) --timeout 900

# The cruising-day suite: every scenarios/cruising/*.toml through
# the daemon, one table of pass/fail and key figures, a PNG plot per scenario
# in $(BUILD)/scenarios. Exits non-zero when a scenario fails.
# Debian's interpreter, where python3-matplotlib is installed (a python3
# earlier on PATH, e.g. a pyenv one, has no matplotlib).
PLOT_PYTHON ?= /usr/bin/python3
scenarios: build deps-tools
	$(PLOT_PYTHON) tests/sim/cruising/suite.py --daemon $(BUILD)/daemon/app/xregulatord --out $(BUILD)/scenarios

# The soak test: the daemon in --sim at speed 20 through a simulated
# day (tests/soak/day.toml) against 20 WebSocket clients, 5 API requests a
# second, dashboard writes and the integrations (mosquitto with the Home
# Assistant publisher, signalk-server from `make deps`, the simulated BMS and
# NMEA 2000 buses). Reports RSS growth after warm-up (the first engine start +
# 30 simulated minutes), overruns (all, and the daemon's own: a tick that used
# a period of CPU time), the store's size and errors; fails on >= 1 MB growth,
# an own overrun or an error. SOAK_S wall seconds: 4320 = 24 simulated hours.
SOAK_S ?= 4320
soak: build
	python3 tests/soak/soak.py --daemon $(BUILD)/daemon/app/xregulatord --duration-s $(SOAK_S) \
	  --www $(BUILD)/web/www --out $(BUILD)/soak

# The phone screenshots of docs/dashboard.md (Live while charging, during a
# fault, the set-up flow, pairing), taken by the browser test against the simulator.
dashboard-screenshots: build
	node tests/web/browser/dashboard.mjs --mode daemon --web-dir web --server $(BUILD)/daemon/app/xregulatord \
	  --www $(BUILD)/web/www --artifacts $(BUILD)/test-artifacts/web --docs-dir docs/img
	node tests/web/browser/weather_panel.mjs --web-dir web --server $(BUILD)/daemon/app/xregulatord \
	  --www $(BUILD)/web/www --root . --docs-dir docs/img
	node tests/web/browser/setup_lfp24.mjs --web-dir web --server $(BUILD)/daemon/app/xregulatord \
	  --www $(BUILD)/web/www --root . --docs-dir docs/img
	node tests/web/browser/events_incident.mjs --web-dir web --server $(BUILD)/daemon/app/xregulatord \
	  --www $(BUILD)/web/www --root . --docs-dir docs/img
	node tests/web/browser/screenshots.mjs --web-dir web --server $(BUILD)/daemon/app/xregulatord \
	  --www $(BUILD)/web/www --root . --docs-dir docs/img
	node tests/web/browser/battery_health.mjs --web-dir web --server $(BUILD)/daemon/app/xregulatord \
	  --www $(BUILD)/web/www --root . --docs-dir docs/img

# make bench measures its own optimised tree (Release, LTO, profile-guided,
# for this machine's CPU: tests/bench/build-pgo.sh) so the figures are what the
# code can do, not what a debug-info build happens to do; results in
# $(BENCH_BUILD)/bench-results.
BENCH_BUILD ?= build-bench
bench: deps-tools
	tests/bench/build-pgo.sh $(BENCH_BUILD) $(JOBS)
	tests/bench/run.sh $(BENCH_BUILD)

# Debian package: dpkg-buildpackage writes beside the source tree; the results
# are moved to $(BUILD)/deb. `make deb ARCH=arm64` (or armhf) cross-builds with
# Debian's cross compilers and multiarch libraries (`make deps-cross`) and
# checks the result: Architecture:, ELF class and machine of every binary, the
# Depends: of that architecture, lintian (tests/package/check_cross.sh).
# ccache is used when installed. `make package-test` also installs, checks and
# purges the native package (slow, so not part of `make test`).
DEB_VERSION = $(shell dpkg-parsechangelog -S Version 2>/dev/null)
HOST_ARCH := $(shell dpkg --print-architecture)
ARCH ?= $(HOST_ARCH)
DEB_DEPS := deps-tools $(if $(filter-out $(HOST_ARCH),$(ARCH)),deps-cross)
# nocheck on a cross build: the package runs no tests (override_dh_auto_test
# is empty), and without it dh warns that tests cannot run cross.
DEB_CROSS_OPTS := $(if $(filter-out $(HOST_ARCH),$(ARCH)),nocheck)
deb: $(DEB_DEPS)
	PATH=/usr/lib/ccache:$$PATH DEB_BUILD_OPTIONS="parallel=$(JOBS) $(DEB_CROSS_OPTS) $$DEB_BUILD_OPTIONS" \
	  dpkg-buildpackage -a$(ARCH) -us -uc -b
	@mkdir -p $(BUILD)/deb
	mv ../xregulator_$(DEB_VERSION)_$(ARCH).* ../xregulator-dbgsym_$(DEB_VERSION)_$(ARCH).* $(BUILD)/deb/
	@ls -l $(BUILD)/deb
	tests/package/check_cross.sh $(ARCH) $(BUILD)/deb/xregulator_$(DEB_VERSION)_$(ARCH).deb \
	  $(BUILD)/deb/xregulator_$(DEB_VERSION)_$(ARCH).changes

.PHONY: package-test
package-test: deps-tools
	tests/package/run.sh

# The signed apt repository (docs/release.md): reprepro, channels stable and
# candidate, from the packages of `make deb` (made first when there are none).
# The signing key comes from GNUPGHOME (never from this tree):
#   make repo REPO_KEY=<signing subkey id> [REPO_CHANNEL=stable] [REPO_DIR=...]
REPO_DIR     ?= $(BUILD)/repo
REPO_CHANNEL ?= candidate
REPO_URL     ?= https://apt.xregulator.example.org/debian
REPO_KEY     ?=
.PHONY: repo update-test
repo:
	@ls $(BUILD)/deb/xregulator_*.deb >/dev/null 2>&1 || $(MAKE) --no-print-directory deb
	tools/update/make-repo.sh --repo $(REPO_DIR) --channel $(REPO_CHANNEL) --key "$(REPO_KEY)" --url $(REPO_URL) \
	  $(BUILD)/deb/xregulator_*.deb

# The owner's update path end to end, as root on this machine (about two
# minutes; tests/update/run.sh says what it covers): CI runs it after `make test`.
update-test: deps-tools $(BUILD)/CMakeCache.txt
	tests/update/run.sh $(BUILD)

# Cross-building for the Pi (docs/install.md): Debian 12's cross compilers,
# qemu-user and the arm64/armhf multiarch libraries. Idempotent like deps.
CROSS_LIBS := libboost1.81-dev libboost-json1.81-dev libgpiod-dev libsqlite3-dev \
  libspdlog-dev libfmt-dev libtomlplusplus-dev libgtest-dev libgmock-dev libsystemd-dev \
  libmosquitto-dev libssl-dev
# pkg-config:<arch> provides <triplet>-pkg-config, which debhelper's cross
# cmake build asks for.
CROSS_LIBS := $(CROSS_LIBS) pkg-config
# ctest package.cross_deps_cover_build_depends reads the list from here.
.PHONY: print-cross-libs
print-cross-libs:
	@echo $(CROSS_LIBS)
# CROSS_ARCHES: the arm64 tests need only arm64 (deps-cross-arm64), so a mirror
# that serves a broken armhf index for a while does not stop them.
CROSS_ARCHES ?= arm64 armhf
CROSS_PACKAGES = qemu-user-static $(foreach a,$(CROSS_ARCHES),crossbuild-essential-$(a) $(addsuffix :$(a),$(CROSS_LIBS)))
.PHONY: deps-cross-arm64
deps-cross-arm64: deps
	@$(MAKE) --no-print-directory deps-cross CROSS_ARCHES=arm64
deps-cross: deps
	@SUDO=""; [ "$$(id -u)" = 0 ] || SUDO=sudo; \
	for a in $(CROSS_ARCHES); do \
	  dpkg --print-foreign-architectures | grep -qx $$a || { $$SUDO dpkg --add-architecture $$a; echo "deps-cross: added $$a"; }; \
	done
	@$(call APT_INSTALL,$(CROSS_PACKAGES),deps-cross)

# The arm64 build under qemu-user (docs/install.md): its own tree (no LTO,
# -O2: GCC 12's -O3 aarch64 -Wrestrict false positive), with the tests. ctest
# runs the unit, driver, closed-loop and web API tests through the toolchain's
# CMAKE_CROSSCOMPILING_EMULATOR (qemu-aarch64-static -L /). Excluded: tests
# whose scripts exec the binary directly (no binfmt_misc here, so an arm
# binary started by a host script fails with "exec format error") or test
# host things (end-to-end exit paths, CLI round trip, browser, dashboard
# units, fuzz, TSAN tree, unit files, source and layout rules, soak smoke,
# cruising and BMS-on-CAN suites, integration daemons, the package and arm
# judges): they stay in `make test`.
# Then: the loader/libc pairing that caused the start-up hang seen under qemu-user and
# a start, run and SIGTERM stop (tests/arm/emulator_check.sh); the 8 h
# LiFePO4 charge on both builds (same stages, energy within 0.1 %); the
# arm64 package (`make deb ARCH=arm64` and its check).
# Also left out: the driver tests that need the kernel to answer an ioctl on a
# plain file with ENOTTY. qemu-user 7.2 does not translate I2C_FUNCS, I2C_RDWR
# or WDIOC_* ("Unsupported ioctl" under -d unimp) and answers ENOSYS itself,
# so the kernel is never asked; they run natively in `make test`, and the
# watchdog ioctls on a real kernel in `make test-kernel` (softdog).
ARM64_BUILD ?= build-arm64
QEMU_AARCH64 ?= qemu-aarch64-static
ARM_QEMU_GAPS := drivers\.LinuxI2cBus\.(RegularFileIsRejectedByTheIoctl|IoctlErrorOnANonAdapterFdIsReturnedNotRetried)|drivers\.LinuxWatchdog\.(PlainFileIsAcceptedButReported|KeepAliveWritesOneNonMagicBytePerCall|MagicCloseOnlyOnCleanStop|NoKeepAliveMeansNoBytes)
ARM_CTEST_EXCLUDE := ^(e2e_|web_browser|web_dashboard_units|web_fuzz|package\.|arm\.|config_cli_roundtrip|runtime_tsan|systemd_units_verify|source_rules\.|layout\.|soak_smoke|cruising\.|bms_can\.|integrations\.|$(ARM_QEMU_GAPS))
test-arm64: deps-cross-arm64 $(BUILD)/CMakeCache.txt
	cmake -S . -B $(ARM64_BUILD) -G Ninja \
	  -DCMAKE_TOOLCHAIN_FILE=cmake/toolchain-aarch64.cmake -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -DNDEBUG" -DXR_LTO=OFF -DXR_BUILD_TESTS=ON -DXR_BUILD_BENCH=OFF \
	  $(if $(shell command -v ccache),-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
	cmake --build $(ARM64_BUILD) -j $(JOBS)
	ctest --test-dir $(ARM64_BUILD) --output-on-failure -j $(JOBS) --timeout 1800 -E '$(ARM_CTEST_EXCLUDE)'
	cmake --build $(BUILD) -j $(JOBS) --target xregulatord
	$(MAKE) --no-print-directory arm-daemon-checks ARM_BUILD=$(ARM64_BUILD) QEMU_ARM=$(QEMU_AARCH64) ARM_TRIPLET=aarch64-linux-gnu
	$(MAKE) --no-print-directory deb ARCH=arm64

# CI's part of test-arm64 (.ci/run, after `make test`, whose host tree it
# reuses): a cold arm64 cross-build of the daemon (277 build steps), then,
# beside the daemon checks and the 8 h comparison, the control, protection,
# parameter, battery, health and closed-loop test binaries (89 steps) and
# those tests under qemu-aarch64-static (each binary in JOBS GoogleTest
# shards, tests/arm/run_gtests.sh). Measured in docs/development.md; the rest
# of the tree and the package stay in `make test-arm64`.
ARM64_CI_TESTS := control_test control_alloc_test protection_test protection_regulator_test \
  params_test battery_test health_test xr_sim_closed_loop_tests
ARM64_CI_BINS := tests/unit/control/control_test tests/unit/control/control_alloc_test \
  tests/unit/protection/protection_test tests/unit/protection/protection_regulator_test \
  tests/unit/params/params_test tests/unit/battery/battery_test tests/unit/health/health_test \
  tests/sim/xr_sim_closed_loop_tests
# On arm64 CI runs the closed-loop tests that end within seconds: the faults,
# the protections and modes, pacing and start-up. Those that run a bank
# through hours of charging (the health days, the belt-slip runs, the stage,
# tail-current, SoC, auto-zero, thermal and battery-temperature runs: 75 % of
# the binary's time, minutes under qemu) run on the host only. On arm64 their
# arithmetic is that of the unit tests above, which run here, and their
# closed loop is judged by the 8 h comparison of the whole daemon below.
ARM64_CI_FILTER := -MeasuredCapacity.*:BatteryResistance.*:BeltSlip.*:BeltSlipTachAlone.*:HealthFromOrdinaryUse.*
ARM64_CI_FILTER := $(ARM64_CI_FILTER):ClosedLoop.AgmAbsorptionEndsOnTailCurrent:ClosedLoop.LfpFullChargeBulkAbsorptionFloat
ARM64_CI_FILTER := $(ARM64_CI_FILTER):ClosedLoop.SocFollowsPlantTruthOverACycle:ClosedLoop.SustainedThermalDerate*
ARM64_CI_FILTER := $(ARM64_CI_FILTER):ClosedLoopMode.AutoZeroCorrectsHallDrift:ClosedLoopScenarios.*
ARM64_CI_FILTER := $(ARM64_CI_FILTER):BatteryTempClosedLoop.HotAgm*:BatteryTempClosedLoop.TwentyFour*:BatteryTempClosedLoop.Cold*
.PHONY: test-arm64-ci
test-arm64-ci: deps-cross-arm64 $(BUILD)/CMakeCache.txt
	cmake -S . -B $(ARM64_BUILD) -G Ninja \
	  -DCMAKE_TOOLCHAIN_FILE=cmake/toolchain-aarch64.cmake -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -DNDEBUG" -DXR_LTO=OFF -DXR_BUILD_TESTS=ON -DXR_BUILD_BENCH=OFF \
	  $(if $(shell command -v ccache),-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
	cmake --build $(ARM64_BUILD) -j $(JOBS) --target xregulatord xregulator-field-off
	cmake --build $(BUILD) -j $(JOBS) --target xregulatord
	@echo "the daemon checks (log at the end) beside the test binaries' build and run: the 8 h run under qemu is one thread"
	@echo "and the longest step, so the build and the tests beside it run at nice 10"
	@$(MAKE) --no-print-directory arm-daemon-checks ARM_BUILD=$(ARM64_BUILD) QEMU_ARM=$(QEMU_AARCH64) \
	  ARM_TRIPLET=aarch64-linux-gnu > $(ARM64_BUILD)/daemon-checks.log 2>&1 & checks=$$!; \
	nice -n 10 cmake --build $(ARM64_BUILD) -j $(JOBS) --target $(ARM64_CI_TESTS) && \
	  GTEST_FILTER='$(ARM64_CI_FILTER)' nice -n 10 tests/arm/run_gtests.sh $(QEMU_AARCH64) / $(JOBS) \
	    $(addprefix $(ARM64_BUILD)/,$(ARM64_CI_BINS)); tests=$$?; \
	wait $$checks; checks_rc=$$?; cat $(ARM64_BUILD)/daemon-checks.log; \
	[ $$tests = 0 ] && [ $$checks_rc = 0 ]

# The daemon checks and the 8 h comparison for one cross tree (arm64 above;
# armhf: `make test-armhf`). The comparison's scenario goes through bulk,
# absorption and float (lfp-charge.toml stays in bulk for its 8 h), and the
# judge fails a run with fewer than 3 stage entries.
ARM_SCENARIO ?= scenarios/lfp-charge-stages.toml
ARM_BUILD ?= build-arm64
QEMU_ARM ?= qemu-aarch64-static
ARM_TRIPLET ?= aarch64-linux-gnu
.PHONY: arm-daemon-checks test-armhf
arm-daemon-checks:
	tests/arm/emulator_check.sh pairing $(QEMU_ARM) / $(ARM_BUILD)/daemon/app/xregulatord
	tests/arm/emulator_check.sh daemon $(QEMU_ARM) / $(ARM_BUILD)/daemon/app/xregulatord
	@tests/arm/emulator_check.sh detects-mismatch $(QEMU_ARM) $(ARM_TRIPLET) $(ARM_BUILD)/daemon/app/xregulatord; \
	  rc=$$?; [ $$rc = 0 ] || [ $$rc = 77 ]
	$(BUILD)/daemon/app/xregulatord --sim --scenario $(ARM_SCENARIO) --speed max \
	  --telemetry-csv $(ARM_BUILD)/lfp-host.csv > $(ARM_BUILD)/lfp-host.log 2>&1 & host=$$!; \
	$(QEMU_ARM) -L / $(ARM_BUILD)/daemon/app/xregulatord --sim --scenario $(ARM_SCENARIO) \
	  --speed max --telemetry-csv $(ARM_BUILD)/lfp-arm.csv > $(ARM_BUILD)/lfp-arm.log 2>&1; arm=$$?; \
	wait $$host; host_rc=$$?; echo "8 h runs: host exit $$host_rc, arm exit $$arm"; [ $$host_rc = 0 ] && [ $$arm = 0 ]
	tests/arm/compare_runs.py --min-stages 3 $(ARM_BUILD)/lfp-host.csv $(ARM_BUILD)/lfp-arm.csv

# 32-bit (armhf) daemon: cross-built daemon only, the same daemon checks and
# 8 h comparison under qemu-arm-static.
ARMHF_BUILD ?= build-armhf
test-armhf: deps-cross $(BUILD)/CMakeCache.txt
	cmake -S . -B $(ARMHF_BUILD) -G Ninja \
	  -DCMAKE_TOOLCHAIN_FILE=cmake/toolchain-armhf.cmake -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -DNDEBUG" -DXR_LTO=OFF -DXR_BUILD_TESTS=OFF -DXR_BUILD_BENCH=OFF \
	  $(if $(shell command -v ccache),-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
	cmake --build $(ARMHF_BUILD) -j $(JOBS) --target xregulatord
	cmake --build $(BUILD) -j $(JOBS) --target xregulatord
	$(MAKE) --no-print-directory arm-daemon-checks ARM_BUILD=$(ARMHF_BUILD) QEMU_ARM=qemu-arm-static ARM_TRIPLET=arm-linux-gnueabihf

# The real-kernel rig (tests/kernel/run.sh, docs/install.md):
# Debian 12's arm64 kernel in qemu-system-aarch64 -M virt (TCG) with an
# initramfs of the arm64 daemon, xregulator-field-off and the rig's helper;
# libgpiod on the virt board's PL061, softdog, vcan, i2c-dev, PWM on tmpfs.
# Prints `N passed, N failed`. Not in `make test` (docs/install.md says why).
KERNEL_PACKAGES := qemu-system-arm cpio
KERNEL_WORK ?= $(ARM64_BUILD)/kernel-rig
.PHONY: test-kernel
test-kernel: deps-cross
	@$(call APT_INSTALL,$(KERNEL_PACKAGES),test-kernel)
	cmake -S . -B $(ARM64_BUILD) -G Ninja \
	  -DCMAKE_TOOLCHAIN_FILE=cmake/toolchain-aarch64.cmake -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -DNDEBUG" -DXR_LTO=OFF -DXR_BUILD_TESTS=ON -DXR_BUILD_BENCH=OFF \
	  $(if $(shell command -v ccache),-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
	cmake --build $(ARM64_BUILD) -j $(JOBS) --target xregulatord xregulator-field-off xr_board_check \
	  $(if $(wildcard tests/kernel/vcan_check.cpp),vcan_check)
	tests/kernel/run.sh $(ARM64_BUILD) $(KERNEL_WORK)

format:
	find daemon drivers web/server tests tools -name '*.cpp' -o -name '*.h' | xargs clang-format -i

clean:
	rm -rf $(BUILD) $(BENCH_BUILD)
