# The knoblab distro's fragments (kept in the checkout's kernel-config/, shared
# with the CI image's kernel). On the 6.12 kernel the distro selects, rt.cfg
# turns on mainline PREEMPT_RT. Other distros get the kernel unchanged.
FILESEXTRAPATHS:prepend:knoblab-distro := "${KNOBLAB_KERNEL_CONFIG_DIR}:"

SRC_URI:append:knoblab-distro = " file://rt.cfg file://loop-core.cfg file://daq.cfg file://display.cfg"
# gpio-sim for the images that run hapticd on simulated lines (ptest, CI).
SRC_URI:append:knoblab-distro = "${@bb.utils.contains('DISTRO_FEATURES', 'ptest', ' file://sim-io.cfg', '', d)}"
