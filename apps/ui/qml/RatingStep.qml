// The rating step after a trial, one scale after another: SAM and the other
// 1–9 scales as a row of big buttons with each end's meaning labelled (the
// protocol's min_is), the affect grid as a 9×9 grid of cells to tap
// (valence across, arousal up). The answers go back when the last is given.
pragma ComponentBehavior: Bound
import QtQuick
import QtQuick.Layouts
import "study.mjs" as Study

Item {
    id: step
    required property var scales  // [{scale, min, max, minIs, prompt}]
    signal submitted(var ratings)

    property int current: 0
    property var answers: ({})
    readonly property var scale: current < scales.length ? scales[current] : ({ scale: "", min: 1, max: 9, minIs: "low", prompt: "" })
    readonly property bool grid: scale.scale === "affect_grid"
    readonly property var labels: Study.endLabels(scale.scale, scale.minIs)

    onScalesChanged: {
        current = 0;
        answers = {};
    }

    function answer(value) {
        const a = step.answers;
        a[step.scale.scale] = value;
        step.answers = a;
        if (step.current + 1 < step.scales.length)
            ++step.current;
        else
            step.submitted(step.answers);
    }

    ColumnLayout {
        anchors.fill: parent
        spacing: Theme.gap * 2

        Text {
            objectName: "ratingPrompt"
            Layout.fillWidth: true
            horizontalAlignment: Text.AlignHCenter
            wrapMode: Text.WordWrap
            text: step.scale.prompt !== "" ? step.scale.prompt : Study.question(step.scale.scale)
            color: Theme.text
            font.pixelSize: Theme.fontTitle
        }

        // SAM and the other scales: min … max, big, with the ends named.
        ColumnLayout {
            visible: !step.grid
            Layout.fillWidth: true
            Layout.fillHeight: true
            spacing: Theme.gap
            Item {
                Layout.fillHeight: true
            }
            RowLayout {
                Layout.fillWidth: true
                spacing: Theme.gap
                Repeater {
                    model: step.grid ? [] : Study.values(step.scale.min, step.scale.max)
                    Rectangle {
                        id: cell
                        required property int modelData
                        objectName: "rate." + modelData
                        Layout.fillWidth: true
                        Layout.preferredHeight: Theme.touch * 1.6
                        radius: Theme.radius
                        color: tap.pressed ? Theme.line : Theme.raised
                        border.color: Theme.accent
                        border.width: 2
                        Text {
                            anchors.centerIn: parent
                            text: cell.modelData
                            color: Theme.text
                            font.pixelSize: Theme.fontTitle
                            font.bold: true
                        }
                        TapHandler {
                            id: tap
                            onTapped: step.answer(cell.modelData)
                        }
                    }
                }
            }
            RowLayout {
                Layout.fillWidth: true
                Text {
                    objectName: "rateMin"
                    text: "← " + step.scale.min + " " + step.labels.min
                    color: Theme.muted
                    font.pixelSize: Theme.fontLarge
                }
                Item {
                    Layout.fillWidth: true
                }
                Text {
                    objectName: "rateMax"
                    text: step.labels.max + " " + step.scale.max + " →"
                    color: Theme.muted
                    font.pixelSize: Theme.fontLarge
                }
            }
            Item {
                Layout.fillHeight: true
            }
        }

        // The affect grid: valence across, arousal up; tap one cell.
        RowLayout {
            visible: step.grid
            Layout.fillWidth: true
            Layout.fillHeight: true
            spacing: Theme.gap
            Item {
                Layout.fillWidth: true
            }
            ColumnLayout {
                Layout.fillHeight: true
                Layout.fillWidth: false
                spacing: Theme.gap / 2
                Text {
                    Layout.alignment: Qt.AlignHCenter
                    text: step.scale.minIs === "high" ? "calm" : "excited"
                    color: Theme.muted
                    font.pixelSize: Theme.fontSmall
                }
                Grid {
                    id: grid
                    objectName: "affectGrid"
                    readonly property int n: step.scale.max - step.scale.min + 1
                    readonly property real cellSize: Math.floor(Math.min(step.height * 0.7, step.width * 0.6) / Math.max(1, n))
                    Layout.alignment: Qt.AlignHCenter
                    columns: n
                    spacing: 2
                    Repeater {
                        model: step.grid ? grid.n * grid.n : 0
                        Rectangle {
                            id: square
                            required property int index
                            readonly property int column: index % grid.n
                            readonly property int row: Math.floor(index / grid.n)
                            objectName: "grid." + column + "." + row
                            width: grid.cellSize - 2
                            height: width
                            color: squareTap.pressed ? Theme.accent
                                                     : (column === (grid.n - 1) / 2 || row === (grid.n - 1) / 2) ? Theme.line : Theme.raised
                            TapHandler {
                                id: squareTap
                                onTapped: {
                                    const g = Study.gridRating(square.column, square.row, step.scale.min, step.scale.max, step.scale.minIs);
                                    step.answer({ valence: g.valence, arousal: g.arousal });
                                }
                            }
                        }
                    }
                }
                RowLayout {
                    Layout.preferredWidth: grid.width
                    Text {
                        text: step.scale.minIs === "high" ? "← pleasant" : "← unpleasant"
                        color: Theme.muted
                        font.pixelSize: Theme.fontSmall
                    }
                    Item {
                        Layout.fillWidth: true
                    }
                    Text {
                        text: step.scale.minIs === "high" ? "excited" : "calm"
                        color: Theme.muted
                        font.pixelSize: Theme.fontSmall
                    }
                    Item {
                        Layout.fillWidth: true
                    }
                    Text {
                        text: step.scale.minIs === "high" ? "unpleasant →" : "pleasant →"
                        color: Theme.muted
                        font.pixelSize: Theme.fontSmall
                    }
                }
            }
            Item {
                Layout.fillWidth: true
            }
        }
    }
}
