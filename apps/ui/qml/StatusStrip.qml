// Always on top: is hapticd there, is its loop turning, and is anything
// stopping the motor (e-stop, amplifier, faults). Tapping "knoblab" goes home.
import QtQuick
import QtQuick.Layouts
import "format.mjs" as Format

Rectangle {
    id: strip
    required property DaemonLink link
    signal homeRequested

    implicitHeight: Theme.stripHeight
    color: Theme.surface

    component Reading: Text {
        property bool ok: true
        color: ok ? Theme.text : Theme.bad
        font.pixelSize: Theme.fontSmall
        font.bold: !ok
        Layout.alignment: Qt.AlignVCenter
    }

    RowLayout {
        anchors.fill: parent
        anchors.leftMargin: Theme.gap
        anchors.rightMargin: Theme.gap
        spacing: Theme.gap * 1.5

        Text {
            text: "knoblab"
            color: Theme.accent
            font.pixelSize: Theme.fontBody
            font.bold: true
            Layout.alignment: Qt.AlignVCenter
            TapHandler {
                onTapped: strip.homeRequested()
            }
        }
        Reading {
            objectName: "connection"
            text: strip.link.connected ? "● hapticd" : "○ hapticd lost"
            ok: strip.link.connected
        }
        Reading {
            objectName: "loop"
            text: "loop " + Format.rate(strip.link.measuredRateHz)
            ok: strip.link.connected && strip.link.measuredRateHz > 0
        }
        Reading {
            objectName: "mode"
            text: strip.link.stateKnown && strip.link.mode !== "" ? strip.link.mode : "–"
        }
        // Without a state read from a live hapticd these say "unknown", not
        // "ok": the e-stop may be pressed for all the kiosk knows.
        Reading {
            objectName: "estop"
            text: !strip.link.stateKnown ? "e-stop unknown" : strip.link.estop ? "E-STOP" : "e-stop ok"
            ok: strip.link.stateKnown && !strip.link.estop
        }
        Reading {
            objectName: "amplifier"
            text: !strip.link.stateKnown ? "amplifier unknown" : strip.link.amplifierFault ? "AMPLIFIER" : "amplifier ok"
            ok: strip.link.stateKnown && !strip.link.amplifierFault
        }
        Reading {
            objectName: "modbus"
            text: "Modbus " + (strip.link.stateKnown ? strip.link.modbus : "unknown")
            ok: strip.link.stateKnown && strip.link.modbusOk
        }
        Reading {
            objectName: "overruns"
            readonly property var overruns: strip.link.stats.overruns
            text: "overruns " + Format.count(overruns !== undefined ? overruns : NaN)
            ok: !(overruns > 0)
        }
        Item {
            Layout.fillWidth: true
        }
        Reading {
            objectName: "faults"
            readonly property int faultCount: strip.link.faults.length
            visible: faultCount > 0
            text: faultCount + (faultCount === 1 ? " fault" : " faults")
            ok: false
        }
    }
}
