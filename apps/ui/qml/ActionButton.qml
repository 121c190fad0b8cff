// A touch button: at least a thumb high, its label never cut.
import QtQuick

Rectangle {
    id: button
    property string text
    property color edge: Theme.accent
    signal activated

    implicitWidth: Math.max(Theme.touch * 2, label.implicitWidth + 3 * Theme.gap)
    implicitHeight: Theme.touch
    radius: Theme.radius
    opacity: enabled ? 1.0 : 0.4
    color: tap.pressed ? Theme.line : Theme.raised
    border.color: edge
    border.width: 2

    Text {
        id: label
        anchors.centerIn: parent
        text: button.text
        color: Theme.text
        font.pixelSize: Theme.fontBody
    }
    TapHandler {
        id: tap
        enabled: button.enabled
        onTapped: button.activated()
    }
}
