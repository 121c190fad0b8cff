// The prototyper's top row: the design's name and file, New, Open, Save,
// Undo and Redo (§5.4: "cycle between previous states"), Play and Stop.
import QtQuick
import QtQuick.Layouts

RowLayout {
    id: bar
    required property DesignSession session
    readonly property bool typing: designName.typing
    // Open shows the designs in the library folder (PrototyperScreen lists them).
    signal openRequested

    spacing: Theme.gap / 2

    Connections {
        target: bar.session
        function onDesignChanged() {
            if (!designName.typing)
                designName.text = bar.session.name;
        }
    }

    SmallField {
        id: designName
        objectName: "designName"
        fieldWidth: 150 * Theme.scale
        Component.onCompleted: designName.text = bar.session.name
        onAccepted: bar.session.renameDesign(designName.text)
    }
    SmallButton {
        objectName: "renameDesign"
        text: "Name"
        enabled: designName.text !== bar.session.name
        onActivated: bar.session.renameDesign(designName.text)
    }
    Text {
        objectName: "designFile"
        Layout.fillWidth: true
        Layout.minimumWidth: 0
        text: (bar.session.fileName !== "" ? bar.session.fileName : "not saved yet") + (bar.session.modified ? " •" : "")
        color: Theme.muted
        font.pixelSize: Theme.fontSmall
        // The file's name may be long: it gives way rather than pushing the buttons off.
        fontSizeMode: Text.HorizontalFit
        minimumPixelSize: 8
    }
    SmallButton {
        objectName: "newDesign"
        text: "New"
        onActivated: bar.session.newDesign()
    }
    SmallButton {
        objectName: "openDesign"
        text: "Open"
        onActivated: bar.openRequested()
    }
    SmallButton {
        objectName: "saveDesign"
        text: "Save"
        onActivated: bar.session.save()
    }
    SmallButton {
        objectName: "undo"
        text: "↶ Undo"
        enabled: bar.session.canUndo
        onActivated: bar.session.undo()
    }
    SmallButton {
        objectName: "redo"
        text: "↷ Redo"
        enabled: bar.session.canRedo
        onActivated: bar.session.redo()
    }
    SmallButton {
        objectName: "play"
        text: bar.session.playing ? "■ Stop" : "▶ Play"
        edge: bar.session.playing ? Theme.warning : Theme.good
        checked: bar.session.playing
        onActivated: bar.session.playing ? bar.session.stop() : bar.session.play()
    }
}
