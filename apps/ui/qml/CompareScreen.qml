// Two knobs side by side: each fitted parameter of A and B with its 95 %
// interval and whether the intervals overlap, and their torque against
// position and against velocity overlaid (A blue, B orange). It runs
// `knoblab compare A B` (each capture's latest stored fit, else fitted now),
// so the numbers are the CLI's.
pragma ComponentBehavior: Bound
import QtQuick
import QtQuick.Layouts
import "format.mjs" as Format

Item {
    id: compare
    required property KnobLibrary knobs
    required property JobRunner jobs
    required property int captureA
    required property int captureB
    // `knoblab compare`'s JSON (params, apart) and its figures' CSVs; null until in.
    property var result: null
    property string failure
    property string figure: "torque_position"

    function label(captureId: int): string {
        // (entries read here: the label follows the library as it is re-read)
        const e = compare.knobs.entries.length >= 0 ? compare.knobs.entry(captureId) : null;
        return (e !== null && e !== undefined && e.knob !== undefined && e.knob !== "" ? e.knob + " · " : "") + "capture " + captureId;
    }
    function run() {
        compare.result = null;
        compare.failure = "";
        if (compare.captureA > 0 && compare.captureB > 0 && !compare.jobs.compare(compare.captureA, compare.captureB))
            compare.failure = "another job is still running: compare again when it is done";
    }
    Component.onCompleted: run()
    onCaptureAChanged: run()
    onCaptureBChanged: run()

    Connections {
        target: compare.jobs
        function onFinished(kind: string, captureId: int, ok: bool, result: var, error: string) {
            if (kind !== "compare" || captureId !== compare.captureA)
                return;
            compare.result = ok ? result : null;
            compare.failure = ok ? "" : error;
        }
    }

    RowLayout {
        anchors.fill: parent
        anchors.margins: Theme.gap
        spacing: Theme.gap

        ColumnLayout {
            Layout.preferredWidth: parent.width * 0.42
            Layout.fillHeight: true
            spacing: Theme.gap / 2

            Text {
                objectName: "compareA"
                Layout.fillWidth: true
                wrapMode: Text.WordWrap
                text: "A  " + compare.label(compare.captureA)
                color: plot.view.colourA
                font.pixelSize: Theme.fontBody
                font.bold: true
            }
            Text {
                objectName: "compareB"
                Layout.fillWidth: true
                wrapMode: Text.WordWrap
                text: "B  " + compare.label(compare.captureB)
                color: plot.view.colourB
                font.pixelSize: Theme.fontBody
                font.bold: true
            }
            Text {
                objectName: "compareVerdict"
                Layout.fillWidth: true
                wrapMode: Text.WordWrap
                text: compare.result !== null
                      ? (compare.result.apart.length === 0 ? "Every parameter judged by its interval overlaps: these could be the same knob."
                                                           : "Apart: " + compare.result.apart.map(n => Format.param(n, 0).label).join(", ") + ".")
                      : compare.failure !== "" ? "Could not compare: " + compare.failure
                      : compare.jobs.running ? "" : "Choose two knobs in the library."
                color: compare.failure !== "" ? Theme.warning : Theme.text
                font.pixelSize: Theme.fontSmall
            }
            ActionButton {
                objectName: "compareAgain"
                visible: compare.failure !== "" && !compare.jobs.running
                text: "Compare again"
                onActivated: compare.run()
            }
            JobProgress {
                jobs: compare.jobs
                visible: compare.jobs.running && compare.jobs.kind === "compare"
                Layout.fillWidth: true
            }
            ListView {
                id: table
                Layout.fillWidth: true
                Layout.fillHeight: true
                clip: true
                spacing: Theme.gap / 2
                model: compare.result !== null ? compare.result.params : []
                delegate: Rectangle {
                    id: row
                    required property var modelData
                    readonly property var a: modelData.a !== null ? Format.param(modelData.name, modelData.a.value, modelData.a.ci95) : null
                    readonly property var b: modelData.b !== null ? Format.param(modelData.name, modelData.b.value, modelData.b.ci95) : null
                    width: ListView.view.width
                    height: cells.implicitHeight + Theme.gap
                    radius: Theme.radius
                    color: Theme.surface
                    border.color: modelData.overlap === false ? Theme.warning : Theme.line
                    GridLayout {
                        id: cells
                        x: Theme.gap / 2
                        y: Theme.gap / 2
                        width: parent.width - Theme.gap
                        columns: 2
                        columnSpacing: Theme.gap / 2
                        rowSpacing: 0
                        Text {
                            Layout.fillWidth: true
                            wrapMode: Text.WordWrap
                            text: (row.a ?? row.b).label
                            color: Theme.muted
                            font.pixelSize: Theme.fontSmall
                        }
                        // The right column one width in every row: the verdicts line up.
                        Text {
                            objectName: "overlap." + row.modelData.name
                            Layout.preferredWidth: Theme.touch * 2.5
                            horizontalAlignment: Text.AlignRight
                            text: row.modelData.overlap === true ? "overlap" : row.modelData.overlap === false ? "apart" : "–"
                            color: row.modelData.overlap === false ? Theme.warning : Theme.muted
                            font.pixelSize: Theme.fontSmall
                            font.bold: row.modelData.overlap === false
                        }
                        Text {
                            objectName: "compare.a." + row.modelData.name
                            Layout.fillWidth: true
                            text: row.a !== null ? row.a.value : "–"
                            color: plot.view.colourA
                            font.pixelSize: Theme.fontBody
                        }
                        Text {
                            Layout.preferredWidth: Theme.touch * 2.5
                            horizontalAlignment: Text.AlignRight
                            text: row.a !== null ? row.a.interval : ""
                            color: Theme.muted
                            font.pixelSize: Theme.fontSmall
                        }
                        Text {
                            objectName: "compare.b." + row.modelData.name
                            Layout.fillWidth: true
                            text: row.b !== null ? row.b.value : "–"
                            color: plot.view.colourB
                            font.pixelSize: Theme.fontBody
                        }
                        Text {
                            Layout.preferredWidth: Theme.touch * 2.5
                            horizontalAlignment: Text.AlignRight
                            text: row.b !== null ? row.b.interval : ""
                            color: Theme.muted
                            font.pixelSize: Theme.fontSmall
                        }
                    }
                }
            }
        }

        ColumnLayout {
            Layout.fillWidth: true
            Layout.fillHeight: true
            spacing: Theme.gap / 2
            Flow {
                Layout.fillWidth: true
                spacing: Theme.gap / 2
                Repeater {
                    model: [["torque · position", "torque_position"], ["torque · velocity", "torque_velocity"]]
                    delegate: ActionButton {
                        required property var modelData
                        objectName: "figure." + modelData[1]
                        text: modelData[0]
                        edge: modelData[1] === compare.figure ? Theme.accent : Theme.line
                        implicitHeight: Theme.touch * 0.75
                        onActivated: compare.figure = modelData[1]
                    }
                }
                ActionButton {
                    objectName: "resetView"
                    text: "Whole figure"
                    implicitHeight: Theme.touch * 0.75
                    onActivated: plot.resetView()
                }
            }
            FigurePane {
                id: plot
                Layout.fillWidth: true
                Layout.fillHeight: true
                csv: compare.result !== null && compare.result.figures[compare.figure] !== undefined ? compare.result.figures[compare.figure] : ""
            }
        }
    }
}
