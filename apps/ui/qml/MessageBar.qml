// Errors and news at the bottom of the screen, never a dialog: the
// experimenter keeps working. Information fades after a few seconds;
// warnings and errors stay until dismissed (or the next message).
import QtQuick

Rectangle {
    id: bar
    property string text
    property string level: "info"

    function show(message, how) {
        bar.text = message;
        bar.level = how;
        bar.visible = true;
        fade.restart();
    }

    visible: false
    height: Math.max(Theme.touch, label.implicitHeight + Theme.gap)
    radius: Theme.radius
    color: level === "error" ? "#5a1f22" : level === "warning" ? "#5a4716" : Theme.raised
    border.color: level === "error" ? Theme.bad : level === "warning" ? Theme.warning : Theme.line

    Text {
        id: label
        objectName: "message"
        anchors.left: parent.left
        anchors.right: close.left
        anchors.verticalCenter: parent.verticalCenter
        anchors.leftMargin: Theme.gap
        text: bar.text
        wrapMode: Text.WordWrap
        color: Theme.text
        font.pixelSize: Theme.fontBody
    }
    Rectangle {
        id: close
        anchors.right: parent.right
        anchors.verticalCenter: parent.verticalCenter
        width: Theme.touch
        height: Theme.touch
        color: "transparent"
        Text {
            anchors.centerIn: parent
            text: "✕"
            color: Theme.text
            font.pixelSize: Theme.fontLarge
        }
        TapHandler {
            onTapped: bar.visible = false
        }
    }
    Timer {
        id: fade
        interval: 4000
        onTriggered: if (bar.level === "info")
            bar.visible = false
    }
}
