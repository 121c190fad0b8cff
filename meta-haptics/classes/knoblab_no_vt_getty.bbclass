# No login prompt on the first VT, where the kiosk draws on the touchscreen:
# getty@tty1 is masked and logind starts no gettys on VT switches. Serial
# consoles keep theirs (serial-getty@).

ROOTFS_POSTPROCESS_COMMAND += "knoblab_no_vt_getty"

# nooelint: oelint.task.docstrings - a rootfs post-process function, not a task
knoblab_no_vt_getty() {
    install -d ${IMAGE_ROOTFS}${sysconfdir}/systemd/system ${IMAGE_ROOTFS}${sysconfdir}/systemd/logind.conf.d
    ln -sf /dev/null ${IMAGE_ROOTFS}${sysconfdir}/systemd/system/getty@tty1.service
    printf '[Login]\nNAutoVTs=0\nReserveVT=0\n' \
        > ${IMAGE_ROOTFS}${sysconfdir}/systemd/logind.conf.d/knoblab-no-vt-getty.conf
}
