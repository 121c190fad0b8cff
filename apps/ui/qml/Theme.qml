// Sizes and colours of every screen, scaled with the panel: 1.0 on a
// 1024×600 panel, 1.33 on 1280×800 (Main sets `scale`). Dark, high-contrast,
// and touch targets no smaller than 64 px at 1.0 (about 9 mm on a 7" panel).
pragma Singleton
import QtQuick

QtObject {
    property real scale: 1.0

    readonly property color background: "#15181c"
    readonly property color surface: "#20252b"
    readonly property color raised: "#2c333b"
    readonly property color line: "#3b444e"
    readonly property color text: "#eef1f4"
    readonly property color muted: "#9aa6b2"
    readonly property color accent: "#4fb3ff"
    readonly property color good: "#4cc38a"
    readonly property color warning: "#f0b429"
    readonly property color bad: "#ff5c5c"

    readonly property int fontSmall: Math.round(15 * scale)
    readonly property int fontBody: Math.round(18 * scale)
    readonly property int fontLarge: Math.round(24 * scale)
    readonly property int fontTitle: Math.round(30 * scale)
    readonly property int touch: Math.round(64 * scale)
    readonly property int gap: Math.round(12 * scale)
    readonly property int radius: Math.round(8 * scale)
    readonly property int stripHeight: Math.round(44 * scale)
}
