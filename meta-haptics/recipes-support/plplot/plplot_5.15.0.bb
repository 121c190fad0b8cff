SUMMARY = "Scientific plotting library"
DESCRIPTION = "PLplot draws 2D and 3D scientific plots. Built here with its C \
               library and the cairo devices only (pdfcairo, pngcairo, svgcairo), \
               which knoblab's fit and discrepancy reports use."
HOMEPAGE = "https://plplot.sourceforge.net/"
BUGTRACKER = "https://sourceforge.net/p/plplot/bugs/"
SECTION = "libs"
LICENSE = "LGPL-2.0-or-later"
LIC_FILES_CHKSUM = "file://COPYING.LIB;md5=3214f080875748938ba060314b4f727d \
                    file://Copyright;md5=9222bd6b5e4e128fac952e168cffc361"
CVE_PRODUCT = "plplot"

DEPENDS:append:class-target = " plplot-native cairo pango"

SRC_URI = "${SOURCEFORGE_MIRROR}/plplot/plplot/${PV}%20Source/plplot-${PV}.tar.gz"
SRC_URI[sha256sum] = "b92de4d8f626a9b20c84fc94f4f6a9976edd76e33fb1eae44f6804bdcc628c7b"

inherit cmake pkgconfig

# Devices compiled into libplplot (no driver modules to find at run time), no
# language bindings beyond C. A cross build imports three generators (font and
# time-scale tables) from plplot-native, as if from a native build directory.
EXTRA_OECMAKE = "-DDEFAULT_NO_BINDINGS=ON -DDEFAULT_NO_DEVICES=ON -DENABLE_DYNDRIVERS=OFF \
                 -DBUILD_TEST=OFF -DBUILD_DOC=OFF -DPREBUILD_DIST=OFF"
EXTRA_OECMAKE:append:class-target = " -DPLD_pdfcairo=ON -DPLD_pngcairo=ON -DPLD_svgcairo=ON"
EXTRA_OECMAKE:append:class-target = " -DCMAKE_NATIVE_BINARY_DIR=${WORKDIR}/native-generators"

do_configure:prepend:class-target() {
    gen=${WORKDIR}/native-generators
    install -d $gen/include $gen/lib/qsastime
    for t in include/ImportExecutables:plhershey-unicode-gen \
             lib/qsastime/tai-utc-gen:tai-utc-gen lib/qsastime/deltaT-gen:deltaT-gen; do
        printf 'add_executable(%s IMPORTED)\nset_property(TARGET %s PROPERTY IMPORTED_LOCATION %s)\n' \
            ${t#*:} ${t#*:} ${STAGING_BINDIR_NATIVE}/${t#*:} > $gen/${t%:*}.cmake
    done
}

do_install:append:class-native() {
    install -m 0755 ${B}/include/plhershey-unicode-gen ${B}/lib/qsastime/tai-utc-gen \
        ${B}/lib/qsastime/deltaT-gen ${D}${bindir}/
}

FILES:${PN} += "${datadir}/plplot${PV}"

BBCLASSEXTEND = "native"
