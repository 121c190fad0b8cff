// A titled panel of a screen.
import QtQuick
import QtQuick.Layouts

Rectangle {
    id: card
    property string title
    default property alias content: body.data
    // The height left for the content under the title: what a scrolling
    // content takes when the card is given its height by a layout.
    readonly property real contentRoom: height - heading.implicitHeight - 3 * Theme.gap

    color: Theme.surface
    radius: Theme.radius
    border.color: Theme.line
    implicitWidth: body.implicitWidth + 2 * Theme.gap
    implicitHeight: heading.implicitHeight + body.implicitHeight + 3 * Theme.gap

    Text {
        id: heading
        x: Theme.gap
        y: Theme.gap
        width: parent.width - 2 * Theme.gap
        text: card.title
        color: Theme.muted
        font.pixelSize: Theme.fontBody
        font.bold: true
    }
    ColumnLayout {
        id: body
        x: Theme.gap
        anchors.top: heading.bottom
        anchors.topMargin: Theme.gap
        width: parent.width - 2 * Theme.gap
        spacing: Theme.gap / 2
    }
}
