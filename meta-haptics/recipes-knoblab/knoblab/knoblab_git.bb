# nooelint: oelint.var.suggestedvar.BUGTRACKER,oelint.var.bbclassextend - no public tracker yet; a device application, no native or SDK build
SUMMARY = "knoblab: capture, model and render the feel of rotary knobs"
DESCRIPTION = "The knoblab lab appliance's software: hapticd (the 10 kHz \
               realtime haptic daemon and its systemd unit), the knoblab \
               command, knoblab-modbus-sim and, when meta-qt6 is in the \
               build, knoblab-ui (the touchscreen kiosk)."
HOMEPAGE = "https://github.com/knoblab/knoblab"
SECTION = "devel"
# The project has chosen no licence yet; CLOSED until it does.
LICENSE = "CLOSED"
CVE_PRODUCT = "knoblab"

DEPENDS = "ceres-solver comedilib hdf5 libeigen libgpiod libmodbus nlohmann-json openssl plplot sqlite3 zlib"

PV = "0.1.0+git"

# No public repository yet: a release build points KNOBLAB_GIT_URI (and
# SRCREV) at one; kas/*.yml build the checkout the layer lives in (externalsrc).
KNOBLAB_GIT_URI ??= "git://github.com/knoblab/knoblab.git;protocol=https;branch=main"
SRC_URI = "${KNOBLAB_GIT_URI};destsuffix=git \
           file://hapticd.json \
           file://ptest-paths.cmake \
           file://run-ptest \
           "
SRCREV ??= "cc46180b6a4c5cbe6ed4d0ca61b5ca7bd26f8d76"

S = "${UNPACKDIR}/git"

inherit cmake pkgconfig systemd useradd ptest features_check

REQUIRED_DISTRO_FEATURES = "systemd"

# tests: for the ptest package. They are listed when ctest runs, not by
# running them at build time (they are target binaries), and the paths they
# were compiled with are rewritten to the device's (ptest-paths.cmake).
# xenomai: hapticd's loop on Xenomai's Cobalt core (kas/xenomai.yml) instead
# of plain Linux / PREEMPT_RT; CMake asks xeno-config for the flags.
PACKAGECONFIG ??= "${@bb.utils.contains('PTEST_ENABLED', '1', 'tests', '', d)}"
PACKAGECONFIG[tests] = "-DKNOBLAB_TESTS=ON -DCMAKE_GTEST_DISCOVER_TESTS_DISCOVERY_MODE=PRE_TEST \
                        -DCMAKE_PROJECT_INCLUDE=${UNPACKDIR}/ptest-paths.cmake \
                        -DKNOBLAB_PTEST_BINDIR=${bindir} -DKNOBLAB_PTEST_DATADIR=${PTEST_PATH}/data, \
                        -DKNOBLAB_TESTS=OFF,googletest libpng"
PACKAGECONFIG[xenomai] = "-DKNOBLAB_RT_BACKEND=xenomai -DKNOBLAB_XENO_CONFIG=${STAGING_BINDIR}/xeno-config, \
                          -DKNOBLAB_RT_BACKEND=posix,xenomai"

# knoblab-ui (the Qt 6 kiosk) needs meta-qt6, which the layer only
# recommends: dynamic-layers/qt6-layer's append turns it on, with its Qt
# dependencies and the knoblab-ui package, when meta-qt6 is in the build.
EXTRA_OECMAKE += "-DKNOBLAB_UI=OFF"

do_configure:prepend() {
    # xeno-config prefixes its paths with DESTDIR: the target sysroot's.
    if ${@bb.utils.contains('PACKAGECONFIG', 'xenomai', 'true', 'false', d)}; then
        export DESTDIR="${STAGING_DIR_HOST}"
    fi
}

do_install:append() {
    # CMake puts the units (hapticd's, and knoblab-ui's when it is built)
    # under ${prefix}/lib; without usrmerge systemd looks in /lib.
    if [ "${prefix}/lib/systemd/system" != "${systemd_system_unitdir}" ]; then
        install -d ${D}${systemd_system_unitdir}
        mv ${D}${prefix}/lib/systemd/system/*.service ${D}${systemd_system_unitdir}/
        rmdir --ignore-fail-on-non-empty ${D}${prefix}/lib/systemd/system ${D}${prefix}/lib/systemd
    fi
    # The default hardware: the simulated camera and in-memory lines. A site
    # layer replaces it with its Comedi and GPIO configuration (docs/hal.md).
    install -D -m 0644 ${UNPACKDIR}/hapticd.json ${D}${sysconfdir}/knoblab/hapticd.json
    # Mount point of the data partition (the root is read-only).
    install -d ${D}${localstatedir}/lib/knoblab
}

do_install_ptest() {
    install -d ${D}${PTEST_PATH}/tests
    install -m 0755 ${B}/tests/*/knoblab_*_tests ${B}/apps/rt/knoblab-rt-bench ${D}${PTEST_PATH}/tests/
    for dir in tests/reference tests/control/corpus; do
        install -d ${D}${PTEST_PATH}/data/$dir
        cp -R --no-dereference --preserve=mode,links ${S}/$dir/. ${D}${PTEST_PATH}/data/$dir/
    done
    install -D -m 0644 ${S}/docs/protocol.md ${D}${PTEST_PATH}/data/docs/protocol.md
    install -D -m 0644 ${S}/apps/hapticd/systemd/hapticd.service \
        ${D}${PTEST_PATH}/data/apps/hapticd/systemd/hapticd.service
}

# The group may use the control socket. The sysusers.d file CMake installs
# names it too, but a read-only root needs it in /etc/group at build time.
USERADD_PACKAGES = "${PN}"
GROUPADD_PARAM:${PN} = "--system knoblab"

SYSTEMD_SERVICE:${PN} = "hapticd.service"

FILES:${PN} += "${nonarch_libdir}/sysusers.d ${localstatedir}/lib/knoblab"
CONFFILES:${PN} = "${sysconfdir}/knoblab/hapticd.json"

RDEPENDS:${PN}-ptest += "${PN}"
