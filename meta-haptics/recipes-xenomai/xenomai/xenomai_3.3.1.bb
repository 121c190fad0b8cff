# nooelint: oelint.var.bbclassextend - needs a Cobalt kernel: target only
SUMMARY = "Xenomai 3 user space for the Cobalt realtime core"
DESCRIPTION = "libcobalt and the other Xenomai 3 libraries, xeno-config and \
               the latency tools, for a kernel with Dovetail and the Cobalt \
               core (linux-dovetail). Built for kas/xenomai.yml, where \
               hapticd's loop runs on Cobalt."
HOMEPAGE = "https://xenomai.org/"
BUGTRACKER = "https://gitlab.com/Xenomai/xenomai3/xenomai/-/issues"
SECTION = "libs"
# Libraries LGPL-2.1; headers GPL-2.0 with a linking exception; utilities
# GPL-2.0; the bundled iniparser MIT.
LICENSE = "LGPL-2.1-only & GPL-2.0-only & MIT"
LIC_FILES_CHKSUM = "file://lib/cobalt/COPYING;md5=68ad62c64cc6c620126241fd429e68fe \
                    file://include/COPYING;md5=79ed705ccb9481bf9e7026b99f4e2b0e \
                    file://kernel/cobalt/COPYING;md5=073dc31ccb2ebed70db54f1e8aeb4c33 \
                    file://lib/boilerplate/iniparser/LICENSE;md5=124f16654dec67923ad76a803e102463"
CVE_PRODUCT = "xenomai"

SRC_URI = "git://source.denx.de/Xenomai/xenomai.git;protocol=https;branch=stable/v3.3.x;destsuffix=git"
# The v3.3.1 tag.
SRCREV = "2f15f8c5970b23428a00ccd17249de26a240dc33"

S = "${UNPACKDIR}/git"

inherit autotools pkgconfig

COMPATIBLE_HOST = "(x86_64|i.86|aarch64|arm).*-linux"

# Only with its kernel (kas/xenomai.yml selects both); elsewhere skipped, as
# linux-yocto-rt is unless it is the kernel.
# nooelint: oelint.task.noanonpython - a parse-time skip needs anonymous python
python () {
    if d.getVar("PREFERRED_PROVIDER_virtual/kernel") != "linux-dovetail":
        raise bb.parse.SkipRecipe("Set PREFERRED_PROVIDER_virtual/kernel to linux-dovetail to enable it")
}

# Headers under /usr/include/xenomai, as xeno-config expects; smp for the
# isolated loop CPU; pshared for objects shared between processes.
EXTRA_OECONF = "--with-core=cobalt --includedir=${includedir}/xenomai \
                --enable-smp --enable-pshared --disable-doc-build"

# knoblab's CMake runs xeno-config from the target sysroot.
SYSROOT_DIRS += "${bindir}"

PACKAGES =+ "${PN}-tools"
FILES:${PN}-tools += "${bindir} ${sbindir} ${libdir}/xenomai ${datadir}/xenomai"
FILES:${PN}-dev += "${libdir}/*.wrappers ${libdir}/dynlist.ld ${libdir}/xenomai/bootstrap*"
RDEPENDS:${PN}-tools += "bash"
