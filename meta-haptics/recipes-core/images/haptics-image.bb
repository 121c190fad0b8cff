# nooelint: oelint.var.suggestedvar.BUGTRACKER,oelint.var.suggestedvar.CVE_PRODUCT - an image: no tracker of its own, no CVE product
SUMMARY = "The knoblab appliance image"
DESCRIPTION = "Boots into hapticd (the realtime haptic daemon) with the \
               knoblab command, the Modbus simulator, rt-tests and, with \
               meta-qt6, the touchscreen kiosk knoblab-ui, on a read-only \
               root with the sqlite store on its own partition."
SECTION = "images"
LICENSE = "MIT"

inherit core-image

IMAGE_INSTALL += "knoblab rt-tests"
# knoblab-ui, the touchscreen kiosk, joins them when meta-qt6 is in the build:
# dynamic-layers/qt6-layer appends it here (with the kiosk's package).

# A wic disk (the .wks files beside this recipe, where scarthgap and later
# releases both look): root, then the data partition, mounted at /var/lib/knoblab once
# /var/lib's volatile overlay is up (the fstab line wic writes says so).
IMAGE_FSTYPES:append = " wic"
WKS_FILE:qemux86-64 = "haptics-qemux86-64.wks"
WKS_FILE:raspberrypi5 = "haptics-raspberrypi.wks"

# runqemu boots the kernel itself (so QB_KERNEL_CMDLINE_APPEND, with the
# loop-CPU isolation, reaches it) and gives it the wic disk's root partition.
QB_DEFAULT_FSTYPE:qemux86-64 = "wic"
QB_FSINFO:qemux86-64 = "wic:no-kernel-in-fs"
QB_KERNEL_ROOT:qemux86-64 = "/dev/sda1 ro"
# Two CPUs at least: CPU 1 is the loop's.
QB_SMP:qemux86-64 = "-smp 2"
