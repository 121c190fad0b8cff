// A short typed value of the prototyper, its label and unit beside it (no
// room above it in the one window). Return applies it, as does the button
// next to it; the on-screen keyboard comes up on the appliance.
import QtQuick
import QtQuick.Controls

Row {
    id: field
    property string label
    property string unit
    property alias text: input.text
    property real fieldWidth: 80 * Theme.scale
    property alias inputMethodHints: input.inputMethodHints
    readonly property bool typing: input.activeFocus
    signal accepted

    spacing: Theme.gap / 3
    height: Math.round(Theme.touch * 0.7)

    Text {
        visible: field.label !== ""
        anchors.verticalCenter: parent.verticalCenter
        text: field.label
        color: Theme.muted
        font.pixelSize: Theme.fontSmall
    }
    TextField {
        id: input
        objectName: field.objectName !== "" ? field.objectName + ".input" : ""
        width: field.fieldWidth
        height: field.height
        font.pixelSize: Theme.fontSmall
        color: Theme.text
        leftPadding: Theme.gap / 2
        rightPadding: Theme.gap / 2
        onAccepted: {
            input.focus = false;
            field.accepted();
        }
        background: Rectangle {
            radius: Theme.radius
            color: Theme.raised
            border.color: input.activeFocus ? Theme.accent : Theme.line
        }
    }
    Text {
        visible: field.unit !== ""
        anchors.verticalCenter: parent.verticalCenter
        text: field.unit
        color: Theme.muted
        font.pixelSize: Theme.fontSmall
    }
}
