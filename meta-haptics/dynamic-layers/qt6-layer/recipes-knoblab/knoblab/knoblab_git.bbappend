# knoblab-ui, the touchscreen kiosk (Qt 6 Quick, apps/ui), when meta-qt6 is in
# the build. qt6-cmake gives CMake the host tools' prefix (QT_HOST_PATH):
# qt_add_qml_module runs qtdeclarative-native's qmltyperegistrar and
# qmlcachegen, moc and rcc come from qtbase-native.
inherit qt6-cmake

DEPENDS:append = " qtbase qtdeclarative qtdeclarative-native qtvirtualkeyboard"

EXTRA_OECMAKE:remove = "-DKNOBLAB_UI=OFF"
EXTRA_OECMAKE += "-DKNOBLAB_UI=ON"

do_install_ptest:append() {
    # The UI's tests stay off the device: they need the offscreen platform,
    # the QML sources and the build tree's module (tests/ui), which the ptest
    # package does not carry.
    rm -f ${D}${PTEST_PATH}/tests/knoblab_ui_*
}

# The binary and its unit, apart from hapticd's package (CMake's "ui"
# component, the CI image's knoblab-ui .deb).
PACKAGE_BEFORE_PN += "${PN}-ui"
FILES:${PN}-ui += "${bindir}/knoblab-ui ${systemd_system_unitdir}/knoblab-ui.service"
SYSTEMD_PACKAGES += "${PN}-ui"
SYSTEMD_SERVICE:${PN}-ui = "knoblab-ui.service"

# What the QML loads at run time (the linked libraries come by themselves), as
# the .deb's dependencies (cmake/packaging.cmake): Qt Quick's and the virtual
# keyboard's QML modules, the keyboard's input context, the SVG image format
# (its key icons), the platform plugins (linuxfb; the knoblab distro builds
# qtbase with it), a font, and ${PN}: hapticd, whose socket it talks to, and
# the knoblab command it runs for fits and discrepancy.
RDEPENDS:${PN}-ui += "\
    ${PN} \
    qtbase-plugins \
    qtdeclarative-qmlplugins \
    qtsvg-plugins \
    qtvirtualkeyboard-plugins \
    qtvirtualkeyboard-qmlplugins \
    ttf-dejavu-sans \
"
