// The pointing task's dial (thesis Figs. 57, 58): a ring with the disk to
// acquire on it (the home disk, then each target) and the needle that
// follows the knob; one revolution of the knob is one turn of the dial,
// θ = 0 at the top and increasing clockwise.
pragma ComponentBehavior: Bound
import QtQuick
import "study.mjs" as Study

Item {
    id: dial
    property bool hasDisk: false
    property real diskCentreDeg: 0
    property real diskWidthDeg: 0
    property bool needle: true
    property real needleDeg: 0

    readonly property real radius: Math.min(width, height) / 2 - Theme.gap
    // The disk's size on the ring: its angular width as an arc, never smaller than a fingertip's dot.
    readonly property real diskSize: Math.max(Theme.gap * 1.5, 2 * Math.PI * radius * diskWidthDeg / 360)

    Rectangle {
        id: ring
        anchors.centerIn: parent
        width: 2 * dial.radius
        height: width
        radius: width / 2
        color: "transparent"
        border.color: Theme.line
        border.width: Math.max(2, Theme.gap / 3)
    }
    // Ticks every 30°.
    Repeater {
        model: 12
        Rectangle {
            id: tick
            required property int index
            x: dial.width / 2 - width / 2
            y: dial.height / 2 - dial.radius
            width: 2
            height: Theme.gap
            color: Theme.muted
            transform: Rotation {
                origin.x: 1
                origin.y: dial.radius
                angle: tick.index * 30
            }
        }
    }
    Rectangle {
        id: disk
        objectName: "disk"
        visible: dial.hasDisk
        width: dial.diskSize
        height: width
        radius: width / 2
        color: Theme.good
        readonly property real a: Study.dialAngle(dial.diskCentreDeg) * Math.PI / 180
        x: dial.width / 2 + dial.radius * Math.sin(disk.a) - disk.width / 2
        y: dial.height / 2 - dial.radius * Math.cos(disk.a) - disk.height / 2
    }
    Rectangle {
        objectName: "needle"
        visible: dial.needle
        x: dial.width / 2 - width / 2
        y: dial.height / 2 - dial.radius - Theme.gap
        width: Math.max(3, Theme.gap / 3)
        height: dial.radius + Theme.gap
        radius: width / 2
        color: Theme.accent
        antialiasing: true
        transform: Rotation {
            origin.x: Math.max(3, Theme.gap / 3) / 2
            origin.y: dial.radius + Theme.gap
            angle: Study.dialAngle(dial.needleDeg)
        }
    }
    Rectangle {
        anchors.centerIn: parent
        width: Theme.gap * 2
        height: width
        radius: width / 2
        color: Theme.accent
    }
}
