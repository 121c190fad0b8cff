// Fit review and discrepancy review: the report's figures of a capture
// (their CSV data, as the CLI stored them with the results), drawn for
// touch: pinch or wheel to zoom, drag to pan, tap for the values at a point.
// Torque against position and against velocity with the model and its 95 %
// band; the residual before and after the findings, against position,
// velocity and time.
pragma ComponentBehavior: Bound
import QtQuick
import QtQuick.Layouts

Item {
    id: review
    required property KnobLibrary knobs
    required property int captureId
    readonly property var entry: knobs.entries.length >= 0 ? knobs.entry(captureId) : null
    readonly property bool fitted: entry !== null && entry.fit !== undefined && entry.fit !== null
    readonly property bool looked: entry !== null && entry.discrepancy !== undefined && entry.discrepancy !== null
    // The figures there are: [label, result kind, file stem].
    readonly property var figures: (fitted ? [["torque · position", "fit", "torque_position"], ["torque · velocity", "fit", "torque_velocity"]] : [])
        .concat(looked ? [["residual · position", "discrepancy", "residual_position"], ["residual · velocity", "discrepancy", "residual_velocity"],
                          ["residual · time", "discrepancy", "residual_time"]] : [])
    property int chosen: 0
    readonly property var figure: chosen < figures.length ? figures[chosen] : null

    function load() {
        if (review.figure === null) {
            plot.csv = "";
            return;
        }
        const id = review.figure[1] === "fit" ? review.entry.fit.id : review.entry.discrepancy.id;
        plot.csv = review.knobs.resultFile(review.figure[1], id, review.figure[2] + ".csv");
    }
    onFigureChanged: load()
    Component.onCompleted: load()

    ColumnLayout {
        anchors.fill: parent
        anchors.margins: Theme.gap
        spacing: Theme.gap / 2

        Text {
            objectName: "reviewTitle"
            Layout.fillWidth: true
            text: review.entry !== null && review.entry.capture_id !== undefined
                  ? (review.entry.knob !== "" ? review.entry.knob : "capture") + " · capture " + review.captureId : "capture " + review.captureId + " is not in the library"
            color: Theme.text
            font.pixelSize: Theme.fontLarge
            font.bold: true
        }
        Text {
            objectName: "reviewEmpty"
            visible: review.figures.length === 0
            Layout.fillWidth: true
            wrapMode: Text.WordWrap
            text: "No figures: fit this capture (or look for discrepancies) from the library first."
            color: Theme.muted
            font.pixelSize: Theme.fontBody
        }
        // Which figure, and which of its panels.
        Flow {
            Layout.fillWidth: true
            spacing: Theme.gap / 2
            Repeater {
                model: review.figures
                delegate: ActionButton {
                    required property var modelData
                    required property int index
                    objectName: "figure." + modelData[2]
                    text: modelData[0]
                    edge: index === review.chosen ? Theme.accent : Theme.line
                    implicitHeight: Theme.touch * 0.75
                    onActivated: review.chosen = index
                }
            }
        }
        Flow {
            Layout.fillWidth: true
            spacing: Theme.gap / 2
            visible: plot.panels.length > 1
            Repeater {
                model: plot.panels
                delegate: ActionButton {
                    required property string modelData
                    objectName: "panel." + modelData
                    text: modelData.replace(/_/g, " ")
                    edge: modelData === plot.panel ? Theme.warning : Theme.line
                    implicitHeight: Theme.touch * 0.75
                    onActivated: plot.panel = modelData
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
            visible: review.figure !== null
        }
    }
}
