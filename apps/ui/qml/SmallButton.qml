// A button of the prototyper's dense panels: shorter than ActionButton (the
// one window holds editor, palette and pane, §5.4), still about 7 mm high
// at 1.0 on a 7" panel. `checked` shows a toggle's state.
import QtQuick

Rectangle {
    id: button
    property string text
    property bool checked: false
    property color edge: Theme.accent
    signal activated

    implicitWidth: Math.max(height * 1.2, label.implicitWidth + 1.5 * Theme.gap)
    implicitHeight: Math.round(Theme.touch * 0.7)
    radius: Theme.radius
    opacity: enabled ? 1.0 : 0.4
    color: tap.pressed ? Theme.line : checked ? "#1d4a6b" : Theme.raised
    border.color: edge
    border.width: checked ? 2 : 1

    Text {
        id: label
        anchors.centerIn: parent
        text: button.text
        color: Theme.text
        font.pixelSize: Theme.fontSmall
    }
    TapHandler {
        id: tap
        enabled: button.enabled
        onTapped: button.activated()
    }
}
