// A main job on the home screen: big enough for a thumb, one word and a line.
import QtQuick

Rectangle {
    id: button
    property string label
    property string detail
    signal activated

    implicitWidth: 260 * Theme.scale
    implicitHeight: 120 * Theme.scale
    radius: Theme.radius
    color: tap.pressed ? Theme.line : Theme.raised
    border.color: Theme.accent
    border.width: 2

    Column {
        anchors.centerIn: parent
        width: parent.width - 2 * Theme.gap
        spacing: Theme.gap / 2
        Text {
            width: parent.width
            horizontalAlignment: Text.AlignHCenter
            text: button.label
            color: Theme.text
            font.pixelSize: Theme.fontLarge
            font.bold: true
        }
        Text {
            width: parent.width
            horizontalAlignment: Text.AlignHCenter
            wrapMode: Text.WordWrap
            text: button.detail
            color: Theme.muted
            font.pixelSize: Theme.fontSmall
        }
    }
    TapHandler {
        id: tap
        onTapped: button.activated()
    }
}
