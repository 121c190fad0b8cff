// The participant's view of a session, the whole screen (Main hides the
// status strip and the message bar): what the study's task shows, by kind —
// pointing: the dial with the knob's needle and the disk to acquire;
// list selection: the counter and the value to find, or "Explore the knob"
// on a blank screen during freeform exploration; matching: the reference
// knob's name and the sliders that change the rendering live; textures: the
// surface being presented — and after each trial the rating step. Nothing of
// the experimenter's: they come back by holding the top-left corner for 2 s.
pragma ComponentBehavior: Bound
import QtQuick
import QtQuick.Controls
import QtQuick.Layouts
import "study.mjs" as Study

Rectangle {
    id: view
    objectName: "participantScreen"
    required property StudySession study
    signal leave

    color: "#000000"
    readonly property bool rating: study.state === "rating"
    readonly property string kind: study.kind

    // The instruction, at the top of every task.
    Text {
        id: instruction
        objectName: "instruction"
        visible: !view.rating && view.study.instruction !== "" && view.kind !== "list_selection"
        anchors.top: parent.top
        anchors.left: parent.left
        anchors.right: parent.right
        anchors.margins: Theme.gap * 2
        horizontalAlignment: Text.AlignHCenter
        wrapMode: Text.WordWrap
        text: view.study.instruction
        color: Theme.text
        font.pixelSize: Theme.fontLarge
    }

    // Pointing.
    PointingDial {
        objectName: "dial"
        visible: !view.rating && view.kind === "pointing"
        anchors.top: instruction.bottom
        anchors.bottom: parent.bottom
        anchors.left: parent.left
        anchors.right: parent.right
        anchors.margins: Theme.gap * 2
        hasDisk: view.study.hasDisk
        diskCentreDeg: view.study.diskCentreDeg
        diskWidthDeg: view.study.diskWidthDeg
        needle: view.study.needle
        needleDeg: view.study.needleDeg
    }

    // List selection: the counter and the target, or the display off.
    ColumnLayout {
        visible: !view.rating && view.kind === "list_selection"
        anchors.centerIn: parent
        width: parent.width - 4 * Theme.gap
        spacing: Theme.gap * 3
        Text {
            objectName: "listTarget"
            visible: view.study.hasTarget
            Layout.alignment: Qt.AlignHCenter
            text: "Find " + view.study.targetValue
            color: Theme.muted
            font.pixelSize: Theme.fontTitle
        }
        // The counter's display, as the list's window on it.
        Rectangle {
            visible: view.study.hasCounter
            Layout.alignment: Qt.AlignHCenter
            implicitWidth: Math.max(counterText.implicitWidth + 8 * Theme.gap, view.width * 0.45)
            implicitHeight: counterText.implicitHeight + 4 * Theme.gap
            radius: Theme.radius * 2
            color: Theme.surface
            border.color: Theme.line
            border.width: 2
            Text {
                id: counterText
                objectName: "listCounter"
                anchors.centerIn: parent
                text: view.study.counter
                color: view.study.counter === view.study.targetValue ? Theme.good : Theme.text
                font.pixelSize: Math.round(140 * Theme.scale)
                font.bold: true
            }
        }
        Text {
            objectName: "listExplore"
            visible: !view.study.hasCounter
            Layout.alignment: Qt.AlignHCenter
            text: view.study.instruction !== "" ? view.study.instruction : " "
            color: Theme.muted
            font.pixelSize: Theme.fontTitle
        }
    }

    // Matching: the reference knob and the sliders.
    ColumnLayout {
        visible: !view.rating && view.kind === "matching"
        anchors.top: instruction.bottom
        anchors.bottom: parent.bottom
        anchors.left: parent.left
        anchors.right: parent.right
        anchors.margins: Theme.gap * 2
        spacing: Theme.gap
        Text {
            objectName: "reference"
            Layout.alignment: Qt.AlignHCenter
            text: "Knob " + view.study.reference
            color: Theme.accent
            font.pixelSize: Theme.fontTitle
            font.bold: true
        }
        Repeater {
            model: view.study.sliderRanges
            RowLayout {
                id: sliderRow
                required property var modelData
                readonly property real value: view.study.sliders[modelData.parameter] !== undefined
                                              ? view.study.sliders[modelData.parameter] : modelData.min
                Layout.fillWidth: true
                spacing: Theme.gap
                Text {
                    text: sliderRow.modelData.label
                    color: Theme.text
                    font.pixelSize: Theme.fontBody
                    Layout.preferredWidth: Math.round(170 * Theme.scale)
                }
                // It moves in position (0 … 1); the session maps a position
                // to the value it sets by the protocol's power law, so equal
                // movements are equal steps of what the participant feels.
                Slider {
                    id: slider
                    objectName: "slider." + sliderRow.modelData.parameter
                    Layout.fillWidth: true
                    Layout.preferredHeight: Theme.touch
                    from: 0
                    to: 1
                    value: view.study.sliderPosition(sliderRow.modelData.parameter, sliderRow.value)
                    live: true
                    onMoved: view.study.setSlider(sliderRow.modelData.parameter,
                                                  view.study.sliderValue(sliderRow.modelData.parameter, slider.value))
                }
                Text {
                    objectName: "sliderValue." + sliderRow.modelData.parameter
                    text: Study.sliderText(view.study.sliderValue(sliderRow.modelData.parameter, slider.value),
                                           sliderRow.modelData.unit)
                    color: Theme.muted
                    font.pixelSize: Theme.fontBody
                    horizontalAlignment: Text.AlignRight
                    Layout.preferredWidth: Math.round(220 * Theme.scale)
                }
            }
        }
        Item {
            Layout.fillHeight: true
        }
        ActionButton {
            objectName: "matchedButton"
            Layout.alignment: Qt.AlignHCenter
            text: "It feels the same: done"
            onActivated: view.study.done()
        }
    }

    // Textures: the surface presented (the participant may be blindfolded).
    ColumnLayout {
        visible: !view.rating && view.kind === "textures"
        anchors.centerIn: parent
        width: parent.width - 4 * Theme.gap
        spacing: Theme.gap * 3
        Rectangle {
            Layout.alignment: Qt.AlignHCenter
            implicitWidth: Math.max(textureText.implicitWidth + 8 * Theme.gap, view.width * 0.5)
            implicitHeight: textureText.implicitHeight + 6 * Theme.gap
            radius: Theme.radius * 2
            color: Theme.surface
            border.color: Theme.line
            border.width: 2
            Text {
                id: textureText
                objectName: "texture"
                anchors.centerIn: parent
                text: view.study.reference
                color: Theme.text
                font.pixelSize: Math.round(48 * Theme.scale)
                font.bold: true
            }
        }
        ActionButton {
            objectName: "strokedButton"
            Layout.alignment: Qt.AlignHCenter
            text: "Done"
            onActivated: view.study.done()
        }
    }

    RatingStep {
        objectName: "ratingStep"
        visible: view.rating
        anchors.fill: parent
        anchors.margins: Theme.gap * 3
        scales: view.study.ratingScales
        onSubmitted: ratings => view.study.submitRatings(ratings)
    }

    // The experimenter's way back: hold the top-left corner.
    Item {
        width: Theme.touch
        height: Theme.touch
        TapHandler {
            longPressThreshold: 2
            onLongPressed: view.leave()
        }
    }
}
