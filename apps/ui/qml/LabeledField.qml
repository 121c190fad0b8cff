// A line of text the experimenter types (the on-screen keyboard comes up on
// the appliance), with its label above.
import QtQuick
import QtQuick.Controls
import QtQuick.Layouts

ColumnLayout {
    id: field
    property string label
    property alias text: input.text
    property alias placeholder: input.placeholderText
    property int maximumLength: 64
    property alias inputMethodHints: input.inputMethodHints
    // Being typed in (a form scrolls it into sight above the keyboard).
    readonly property bool typing: input.activeFocus
    spacing: 4

    Text {
        text: field.label
        color: Theme.muted
        font.pixelSize: Theme.fontSmall
    }
    TextField {
        id: input
        objectName: field.objectName !== "" ? field.objectName + ".input" : ""
        Layout.fillWidth: true
        Layout.preferredHeight: Theme.touch
        maximumLength: field.maximumLength
        font.pixelSize: Theme.fontBody
        color: Theme.text
        placeholderTextColor: Theme.muted
        background: Rectangle {
            radius: Theme.radius
            color: Theme.raised
            border.color: input.activeFocus ? Theme.accent : Theme.line
        }
    }
}
