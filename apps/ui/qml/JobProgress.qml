// A fit or discrepancy run in progress: its stage, a bar when the stage
// counts, and Cancel (the command stops and stores nothing).
import QtQuick
import QtQuick.Layouts

ColumnLayout {
    id: progress
    required property JobRunner jobs
    spacing: Theme.gap / 2
    visible: jobs.running

    Text {
        objectName: "jobStage"
        Layout.fillWidth: true
        wrapMode: Text.WordWrap
        text: "knoblab " + progress.jobs.kind + ": " + progress.jobs.stage
        color: Theme.text
        font.pixelSize: Theme.fontBody
    }
    RowLayout {
        Layout.fillWidth: true
        spacing: Theme.gap
        Rectangle {
            Layout.fillWidth: true
            Layout.preferredHeight: Theme.gap
            radius: height / 2
            color: Theme.raised
            Rectangle {
                // Without a count the bar runs back and forth: busy, not stuck.
                property real busy
                width: progress.jobs.fraction >= 0 ? parent.width * progress.jobs.fraction : parent.width / 4
                x: progress.jobs.fraction >= 0 ? 0 : busy * (parent.width - width)
                height: parent.height
                radius: height / 2
                color: Theme.accent
                SequentialAnimation on busy {
                    running: progress.jobs.running && progress.jobs.fraction < 0
                    loops: Animation.Infinite
                    NumberAnimation { from: 0; to: 1; duration: 900 }
                    NumberAnimation { from: 1; to: 0; duration: 900 }
                }
            }
        }
        ActionButton {
            objectName: "cancelJob"
            text: "Cancel"
            edge: Theme.warning
            onActivated: progress.jobs.cancel()
        }
    }
}
