# The touchscreen kiosk, whose package exists when meta-qt6 is in the build
# (the knoblab append beside this one).
IMAGE_INSTALL += "knoblab-ui"
