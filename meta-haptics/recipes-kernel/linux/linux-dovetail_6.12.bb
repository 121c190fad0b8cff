# nooelint: oelint.var.suggestedvar.BUGTRACKER,oelint.var.bbclassextend - Xenomai's tracker is the xenomai recipe's; a kernel has no native build
SUMMARY = "Linux with Dovetail and Xenomai 3's Cobalt core"
DESCRIPTION = "The kernel of kas/xenomai.yml: linux-dovetail with Xenomai's \
               Cobalt core patched in by its prepare-kernel.sh, configured \
               from the architecture's defconfig and knoblab's fragments."
HOMEPAGE = "https://xenomai.org/"
SECTION = "kernel"
LICENSE = "GPL-2.0-only"
LIC_FILES_CHKSUM = "file://COPYING;md5=6bc538ed5bd9a7fc9398086aedcd7e46"
CVE_PRODUCT = "linux_kernel"

DEPENDS += "elfutils-native openssl-native util-linux-native"

# nooelint: oelint.file.requirenotfound - in poky's meta layer
require recipes-kernel/linux/linux-yocto.inc

# Skipped unless it is the kernel, as linux-yocto-rt is.
# nooelint: oelint.task.noanonpython - a parse-time skip needs anonymous python
python () {
    if d.getVar("KERNEL_PACKAGE_NAME") == "kernel" and d.getVar("PREFERRED_PROVIDER_virtual/kernel") != "linux-dovetail":
        raise bb.parse.SkipRecipe("Set PREFERRED_PROVIDER_virtual/kernel to linux-dovetail to enable it")
}

LINUX_VERSION = "6.12.8"
PV = "${LINUX_VERSION}+git"

# The shared fragments live outside the layer, in the checkout's kernel-config/.
# nooelint: oelint.vars.fileextrapaths,oelint.vars.outofcontext - the fragments are outside the layer, not in files/
FILESEXTRAPATHS:prepend := "${KNOBLAB_KERNEL_CONFIG_DIR}:"

KBRANCH = "v6.12.y-dovetail-rebase"
SRC_URI = "git://source.denx.de/Xenomai/linux-dovetail.git;protocol=https;branch=${KBRANCH};name=machine \
           git://source.denx.de/Xenomai/xenomai.git;protocol=https;branch=stable/v3.3.x;name=xenomai;destsuffix=xenomai \
           file://xenomai.cfg \
           file://loop-core.cfg \
           file://daq.cfg \
           ${@bb.utils.contains('DISTRO_FEATURES', 'ptest', 'file://sim-io.cfg', '', d)} \
           "
# The rebase branch moves: this is its 6.12.8 head that Toradex's Xenomai 3
# layer builds; the Cobalt core is Xenomai v3.3.1, as the xenomai recipe's.
SRCREV_machine = "ed55d775d3b3df3948c43598e7a68be7c0737392"
SRCREV_xenomai = "2f15f8c5970b23428a00ccd17249de26a240dc33"
SRCREV_FORMAT = "machine_xenomai"

KERNEL_VERSION_SANITY_SKIP = "1"

# No yocto-kernel-cache description for this tree: the in-tree defconfig plus
# the fragments above. rt.cfg is left out: Cobalt and PREEMPT_RT exclude each other.
KBUILD_DEFCONFIG:qemux86-64 = "x86_64_defconfig"
KCONFIG_MODE = "alldefconfig"
COMPATIBLE_MACHINE = "^(qemux86-64)$"

do_patch:append() {
    ${UNPACKDIR}/xenomai/scripts/prepare-kernel.sh --linux=${S} --arch=${ARCH}
}
