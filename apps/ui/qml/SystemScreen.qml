// The loop's health, live: rate, overruns and the wake-up latency
// histogram (from hapticd's once-a-second stats); the latched faults with a
// way to clear them; the sensor calibration in use and its age.
pragma ComponentBehavior: Bound
import QtQuick
import QtQuick.Layouts
import "format.mjs" as Format

Item {
    id: system
    required property DaemonLink link
    readonly property var stats: link.stats
    readonly property var calibration: link.state.calibration !== undefined ? link.state.calibration : ({})

    component Row2: RowLayout {
        id: row
        property string name
        property string value
        property bool ok: true
        Layout.fillWidth: true
        Text {
            text: row.name
            color: Theme.muted
            font.pixelSize: Theme.fontBody
            Layout.fillWidth: true
        }
        Text {
            objectName: row.objectName !== "" ? row.objectName + ".value" : ""
            text: row.value
            color: row.ok ? Theme.text : Theme.bad
            font.pixelSize: Theme.fontBody
        }
    }

    GridLayout {
        anchors.fill: parent
        anchors.margins: Theme.gap
        columns: 2
        columnSpacing: Theme.gap
        rowSpacing: Theme.gap
        uniformCellWidths: true

        Card {
            title: "Loop"
            Layout.fillWidth: true
            Layout.fillHeight: true
            Row2 {
                objectName: "rate"
                name: "rate (set / measured)"
                value: Format.rate(system.link.state.rate_hz) + " / " + Format.rate(system.link.measuredRateHz)
            }
            Row2 {
                name: "cycles"
                value: Format.count(system.link.state.cycles)
            }
            Row2 {
                name: "overruns (most in a row)"
                value: Format.count(system.stats.overruns) + " (" + Format.count(system.stats.max_consecutive_overruns) + ")"
                ok: !(system.stats.overruns > 0)
            }
            Row2 {
                objectName: "wakeup"
                name: "wake-up latency p99 / max"
                value: system.stats.wakeup_latency_us !== undefined
                       ? Format.micros(system.stats.wakeup_latency_us.p99) + " / " + Format.micros(system.stats.wakeup_latency_us.max) : "–"
            }
            Row2 {
                name: "cycle cost p99 / max"
                value: system.stats.cycle_cost_us !== undefined
                       ? Format.micros(system.stats.cycle_cost_us.p99) + " / " + Format.micros(system.stats.cycle_cost_us.max) : "–"
            }
        }

        Card {
            id: histogram
            title: "Wake-up latency since start"
            Layout.fillWidth: true
            Layout.fillHeight: true
            readonly property var bins: system.stats.wakeup_histogram_us !== undefined ? system.stats.wakeup_histogram_us : ({ upper: [], counts: [] })
            readonly property real most: Math.max(1, ...bins.counts)

            Item {
                Layout.fillWidth: true
                Layout.preferredHeight: 140 * Theme.scale
                Row {
                    id: bars
                    anchors.fill: parent
                    spacing: 2
                    Repeater {
                        model: histogram.bins.counts
                        delegate: Item {
                            id: bar
                            required property int index
                            required property real modelData
                            width: (bars.width - (histogram.bins.counts.length - 1) * bars.spacing) / Math.max(1, histogram.bins.counts.length)
                            height: bars.height
                            // Log scale: one sample shows as a sliver, the bulk as the full height.
                            Rectangle {
                                anchors.bottom: parent.bottom
                                width: parent.width
                                height: bar.modelData > 0 ? Math.max(3, parent.height * Math.log(1 + bar.modelData) / Math.log(1 + histogram.most)) : 0
                                color: bar.index >= histogram.bins.upper.length ? Theme.bad : Theme.accent
                            }
                        }
                    }
                }
            }
            RowLayout {
                Layout.fillWidth: true
                Text {
                    text: "1 µs"
                    color: Theme.muted
                    font.pixelSize: Theme.fontSmall
                }
                Item {
                    Layout.fillWidth: true
                }
                Text {
                    text: "log time →  > 2 ms"
                    color: Theme.muted
                    font.pixelSize: Theme.fontSmall
                }
            }
            Text {
                objectName: "histogramNote"
                Layout.fillWidth: true
                wrapMode: Text.WordWrap
                text: histogram.bins.counts.length > 0 ? "bars: cycles per doubling bin, on a log scale" : "waiting for hapticd's loop statistics"
                color: Theme.muted
                font.pixelSize: Theme.fontSmall
            }
        }

        Card {
            title: "Faults"
            Layout.fillWidth: true
            Layout.fillHeight: true
            Text {
                objectName: "noFaults"
                visible: system.link.faults.length === 0
                text: system.link.connected ? "none latched" : "unknown: hapticd not connected"
                color: system.link.connected ? Theme.good : Theme.warning
                font.pixelSize: Theme.fontBody
            }
            Repeater {
                model: system.link.faults
                delegate: Text {
                    required property string modelData
                    objectName: "fault"
                    Layout.fillWidth: true
                    wrapMode: Text.WordWrap
                    text: "● " + Format.fault(modelData)
                    color: Theme.bad
                    font.pixelSize: Theme.fontBody
                }
            }
            ActionButton {
                objectName: "clearFaults"
                visible: system.link.faults.length > 0
                text: "Clear faults"
                edge: Theme.warning
                onActivated: system.link.clearFault()
            }
        }

        Card {
            id: calibrationCard
            title: "Sensor calibration"
            Layout.fillWidth: true
            Layout.fillHeight: true
            readonly property var constants: system.calibration.constants !== undefined ? system.calibration.constants : ({})
            readonly property var accepted: system.calibration.accepted !== undefined ? system.calibration.accepted : ({})
            Row2 {
                name: "accelerometer gain C_cal"
                value: calibrationCard.constants.C_cal !== undefined ? Number(calibrationCard.constants.C_cal).toPrecision(4) : "–"
            }
            Row2 {
                name: "torque sensor"
                value: calibrationCard.constants.torque_Nm_per_V !== undefined ? (1000 * calibrationCard.constants.torque_Nm_per_V).toPrecision(3) + " mN·m/V" : "–"
            }
            Row2 {
                name: "accepted: C_cal"
                readonly property var run: calibrationCard.accepted.accel_gain
                value: run !== undefined ? Format.age(Date.now() / 1000 - run.unix_time) : "not since start"
                ok: run !== undefined
            }
            Row2 {
                name: "accepted: gravity (Eq. 2)"
                readonly property var run: calibrationCard.accepted.gravity
                value: run !== undefined ? Format.age(Date.now() / 1000 - run.unix_time) : "not since start"
                ok: run !== undefined
            }
        }
    }
}
