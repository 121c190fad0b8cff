# KNOBLAB_KERNEL_CMDLINE: the kernel command line kept in the checkout's
# kernel-config/cmdline.txt, shared with the CI image. A recipe that expands it
# is parsed again when the file changes.

def knoblab_kernel_cmdline(d):
    path = os.path.join(d.getVar('KNOBLAB_KERNEL_CONFIG_DIR'), 'cmdline.txt')
    bb.parse.mark_dependency(d, path)
    with open(path) as f:
        return ' '.join(f.read().split())

KNOBLAB_KERNEL_CMDLINE = "${@knoblab_kernel_cmdline(d)}"
