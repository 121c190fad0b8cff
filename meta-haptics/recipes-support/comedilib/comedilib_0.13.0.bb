# nooelint: oelint.var.bbclassextend - talks to Comedi devices: target only
SUMMARY = "User-space library for Comedi data acquisition devices"
DESCRIPTION = "comedilib talks to the kernel's Comedi drivers (ADC, DAC, \
               counters); hapticd's Comedi DAQ backend uses it. Also \
               comedi_config, comedi_board_info and comedi_test."
HOMEPAGE = "https://www.comedi.org/"
BUGTRACKER = "https://github.com/Linux-Comedi/comedilib/issues"
SECTION = "libs"
# The library is LGPL-2.1 (COPYING), the utilities GPL-2.0 or later.
LICENSE = "LGPL-2.1-or-later & GPL-2.0-or-later"
LIC_FILES_CHKSUM = "file://COPYING;md5=d8045f3b8f929c1cb29a1e3fd737b499 \
                    file://comedi_config/comedi_config.c;beginline=8;endline=20;md5=b3283b952672bed32bedd7ace8012cc3"
CVE_PRODUCT = "comedilib"

DEPENDS = "bison-native flex-native"

SRC_URI = "git://github.com/Linux-Comedi/comedilib.git;protocol=https;branch=master;destsuffix=git"
# The r0_13_0 tag.
SRCREV = "0daef9e0af61ddb09411b1218e9d3238753e0799"

S = "${UNPACKDIR}/git"

inherit autotools pkgconfig

# No SWIG bindings and no DocBook manual.
EXTRA_OECONF = "--disable-swig --disable-python-binding --disable-ruby-binding --disable-doc"

PACKAGES =+ "${PN}-utils"
FILES:${PN}-utils += "${bindir} ${sbindir}"
