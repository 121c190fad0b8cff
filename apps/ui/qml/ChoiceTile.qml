// One of a few choices, as a big tile: a word and a line, the chosen one lit.
import QtQuick

Rectangle {
    id: tile
    property string label
    property string detail
    property bool chosen: false
    signal activated

    implicitWidth: 300 * Theme.scale
    implicitHeight: 130 * Theme.scale
    radius: Theme.radius
    color: chosen ? "#1d3a52" : (tap.pressed ? Theme.line : Theme.raised)
    border.color: chosen ? Theme.accent : Theme.line
    border.width: chosen ? 3 : 1

    Column {
        anchors.centerIn: parent
        width: parent.width - 2 * Theme.gap
        spacing: Theme.gap / 2
        Text {
            width: parent.width
            horizontalAlignment: Text.AlignHCenter
            text: tile.label
            color: Theme.text
            font.pixelSize: Theme.fontLarge
            font.bold: true
        }
        Text {
            width: parent.width
            horizontalAlignment: Text.AlignHCenter
            wrapMode: Text.WordWrap
            text: tile.detail
            color: Theme.muted
            font.pixelSize: Theme.fontSmall
        }
    }
    TapHandler {
        id: tap
        onTapped: tile.activated()
    }
}
