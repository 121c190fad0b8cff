// The first screen: the main jobs as big buttons, and what hapticd is doing.
import QtQuick
import QtQuick.Layouts

Item {
    id: home
    required property DaemonLink link
    signal open(string screen)

    ColumnLayout {
        anchors.fill: parent
        anchors.margins: Theme.gap * 2
        spacing: Theme.gap * 2

        Text {
            text: "Haptic Camera and knob lab"
            color: Theme.text
            font.pixelSize: Theme.fontTitle
            font.bold: true
        }
        Text {
            objectName: "daemonStatus"
            Layout.fillWidth: true
            wrapMode: Text.WordWrap
            text: home.link.connected
                  ? "hapticd is " + (home.link.mode !== "" ? home.link.mode : "starting")
                    + (home.link.state.recording ? ", recording" : "") + "."
                  : "Waiting for hapticd at " + home.link.socket + (home.link.problem !== "" ? " (" + home.link.problem + ")" : "") + "."
            color: Theme.muted
            font.pixelSize: Theme.fontBody
        }
        GridLayout {
            columns: 3
            columnSpacing: Theme.gap * 2
            rowSpacing: Theme.gap * 2
            BigButton {
                objectName: "captureButton"
                label: "Capture a knob"
                detail: "mount, check the sensors, capture, fit and find what is missing"
                onActivated: home.open("capture")
            }
            BigButton {
                objectName: "libraryButton"
                label: "Knob library"
                detail: "captured knobs, their fits and what the model leaves out"
                onActivated: home.open("library")
            }
            BigButton {
                objectName: "studyButton"
                label: "User study"
                detail: "run a participant's session: experimenter and participant views"
                onActivated: home.open("study")
            }
            BigButton {
                objectName: "prototyperButton"
                label: "Prototyper"
                detail: "design how a knob feels: waveforms, tiles, play them"
                onActivated: home.open("prototyper")
            }
            BigButton {
                objectName: "systemButton"
                label: "System"
                detail: "loop timing, faults, calibration"
                onActivated: home.open("system")
            }
        }
        Item {
            Layout.fillHeight: true
        }
    }
}
