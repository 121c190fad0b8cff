# Debian packages, one per install component, for images built from Debian
# packages (scripts/image/debs.sh runs `cpack -G DEB` in the SDK, which is the
# same Debian release as the image, so dpkg-shlibdeps names the right
# library packages as dependencies).
set(CPACK_PACKAGE_NAME knoblab)
set(CPACK_PACKAGE_VENDOR knoblab)
set(CPACK_PACKAGE_CONTACT "knoblab developers <dev@knoblab.invalid>")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_COMPONENTS_ALL hapticd cli modbus-sim)
if(KNOBLAB_UI)
  list(APPEND CPACK_COMPONENTS_ALL ui)
endif()
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_SECTION misc)
set(CPACK_DEBIAN_HAPTICD_PACKAGE_NAME knoblab-hapticd)
set(CPACK_COMPONENT_HAPTICD_DESCRIPTION "knoblab realtime haptic daemon and its systemd unit")
set(CPACK_DEBIAN_CLI_PACKAGE_NAME knoblab-cli)
set(CPACK_COMPONENT_CLI_DESCRIPTION "the knoblab command: simulate, capture, fit, store, ctl")
set(CPACK_DEBIAN_MODBUS-SIM_PACKAGE_NAME knoblab-modbus-sim)
set(CPACK_COMPONENT_MODBUS-SIM_DESCRIPTION "simulator of the servo amplifier and biometrics box (Modbus TCP)")
set(CPACK_DEBIAN_UI_PACKAGE_NAME knoblab-ui)
set(CPACK_COMPONENT_UI_DESCRIPTION "knoblab touchscreen front-end (Qt 6 Quick kiosk) and its systemd unit")
# What the QML loads at run time (dpkg-shlibdeps sees only the linked
# libraries): Qt Quick's modules, the framebuffer platform plugin, a font, and
# the knoblab command that runs fits and discrepancy.
set(CPACK_DEBIAN_UI_PACKAGE_DEPENDS
    "knoblab-cli, qml6-module-qtquick, qml6-module-qtquick-controls, qml6-module-qtquick-layouts, qml6-module-qtquick-templates, qml6-module-qtquick-window, qml6-module-qtqml-workerscript, qml6-module-qtquick-virtualkeyboard, qt6-virtualkeyboard-plugin, qt6-svg-plugins, hunspell-en-gb, hunspell-en-us, qt6-qpa-plugins, fonts-dejavu-core")
include(CPack)
