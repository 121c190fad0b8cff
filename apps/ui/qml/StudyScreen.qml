// The experimenter's view of a user study: choose a protocol and type the
// participant's pseudonymous code, start (a session that exists resumes)
// and stop; follow the session (trial k of N, block, stage, condition, the
// last trials stored); keep think-aloud notes and free-text tags with the
// running trial; for a matching study, keep the participant's words for
// each slider (Slider tags); hand the screen to the participant
// (Participant view).
pragma ComponentBehavior: Bound
import QtQuick
import QtQuick.Layouts
import "study.mjs" as Study

Item {
    id: screen
    required property StudySession study
    property bool keyboardUp: false
    signal participantView

    property int chosen: 0
    readonly property var protocol: study.protocols.length > 0 ? study.protocols[Math.min(chosen, study.protocols.length - 1)] : ({ title: "No protocols found", kind: "", path: "", study: "" })
    readonly property bool active: study.state === "running" || study.state === "rating"
    // The slider tags take the progress card's place while they are typed.
    property bool tagsOpen: false
    readonly property bool tagsOffered: study.kind === "matching" && study.protocolSliders.length > 0 && study.state !== "idle"
    onTagsOfferedChanged: if (!tagsOffered)
        tagsOpen = false

    RowLayout {
        anchors.fill: parent
        anchors.margins: Theme.gap
        spacing: Theme.gap

        // The session: which protocol, which participant, start and stop.
        Card {
            title: "Session"
            Layout.fillHeight: true
            Layout.preferredWidth: parent.width * 0.44

            RowLayout {
                Layout.fillWidth: true
                spacing: Theme.gap
                enabled: !screen.active
                ActionButton {
                    text: "‹"
                    implicitWidth: Theme.touch
                    onActivated: screen.chosen = (screen.chosen + screen.study.protocols.length - 1) % Math.max(1, screen.study.protocols.length)
                }
                ColumnLayout {
                    Layout.fillWidth: true
                    spacing: 2
                    Text {
                        objectName: "protocolTitle"
                        Layout.fillWidth: true
                        text: screen.active ? screen.study.title : screen.protocol.title
                        wrapMode: Text.WordWrap
                        maximumLineCount: 3
                        color: Theme.text
                        font.pixelSize: Theme.fontBody
                    }
                    Text {
                        objectName: "protocolKind"
                        text: screen.active ? screen.study.kind.replace("_", " ") + " · running"
                                            : (screen.protocol.kind + "").replace("_", " ") + " · " + (screen.chosen + 1) + " of " + screen.study.protocols.length
                        color: Theme.muted
                        font.pixelSize: Theme.fontSmall
                    }
                }
                ActionButton {
                    text: "›"
                    implicitWidth: Theme.touch
                    onActivated: screen.chosen = (screen.chosen + 1) % Math.max(1, screen.study.protocols.length)
                }
            }
            LabeledField {
                id: code
                objectName: "participantCode"
                Layout.fillWidth: true
                enabled: !screen.active
                label: "Participant code (pseudonymous, e.g. P07)"
                text: screen.study.participant
                maximumLength: 16
                inputMethodHints: Qt.ImhNoAutoUppercase | Qt.ImhPreferUppercase | Qt.ImhNoPredictiveText
            }
            RowLayout {
                Layout.fillWidth: true
                spacing: Theme.gap
                ActionButton {
                    objectName: "startButton"
                    text: "Start"
                    enabled: !screen.active && screen.protocol.path !== ""
                    onActivated: screen.study.start(screen.protocol.path, code.text.trim())
                }
                ActionButton {
                    objectName: "stopButton"
                    text: "Stop"
                    edge: Theme.bad
                    enabled: screen.active
                    onActivated: screen.study.stop()
                }
                Item {
                    Layout.fillWidth: true
                }
            }
            RowLayout {
                Layout.fillWidth: true
                spacing: Theme.gap
                ActionButton {
                    objectName: "participantViewButton"
                    Layout.fillWidth: true
                    text: "Participant view"
                    enabled: screen.active
                    onActivated: screen.participantView()
                }
                ActionButton {
                    objectName: "sliderTagsButton"
                    visible: screen.tagsOffered
                    text: "Slider tags"
                    onActivated: screen.tagsOpen = !screen.tagsOpen
                }
            }
            Text {
                Layout.fillWidth: true
                visible: !screen.keyboardUp
                wrapMode: Text.WordWrap
                text: "The participant sees only their task. Hold the top-left corner of their screen for 2 s to come back."
                color: Theme.muted
                font.pixelSize: Theme.fontSmall
            }
        }

        ColumnLayout {
            Layout.fillWidth: true
            Layout.fillHeight: true
            spacing: Theme.gap

            // Where the session is.
            Card {
                title: "Progress"
                visible: !screen.tagsOpen
                Layout.fillWidth: true
                Layout.fillHeight: true
                Text {
                    objectName: "sessionState"
                    Layout.fillWidth: true
                    text: Study.stateText(screen.study.state, screen.study.message)
                          + (screen.study.participant !== "" && screen.study.state !== "idle" ? " · " + screen.study.participant : "")
                          + (screen.study.simulated ? " · simulated" : "")
                    elide: Text.ElideNone
                    wrapMode: Text.WordWrap
                    maximumLineCount: 2
                    color: screen.study.state === "error" ? Theme.bad : Theme.text
                    font.pixelSize: Theme.fontBody
                    font.bold: true
                }
                Text {
                    objectName: "sessionProgress"
                    Layout.fillWidth: true
                    wrapMode: Text.WordWrap
                    text: Study.progress(screen.study.trial, screen.study.trials, screen.study.block, screen.study.practice, screen.study.stage)
                          + (screen.study.resumedAt > 1 ? " (resumed at " + screen.study.resumedAt + ")" : "")
                    color: Theme.text
                    font.pixelSize: Theme.fontBody
                }
                Text {
                    objectName: "sessionCondition"
                    Layout.fillWidth: true
                    wrapMode: Text.WordWrap
                    text: screen.study.condition !== "" ? screen.study.condition : "–"
                    color: Theme.accent
                    font.pixelSize: Theme.fontSmall
                }
                Text {
                    text: "Last trials stored (" + screen.study.committed + ")"
                    color: Theme.muted
                    font.pixelSize: Theme.fontSmall
                }
                Repeater {
                    model: screen.study.recentTrials.slice(0, screen.keyboardUp ? 0 : Theme.scale > 1.1 ? 5 : 3)
                    Text {
                        required property var modelData
                        required property int index
                        objectName: "recent." + index
                        Layout.fillWidth: true
                        elide: Text.ElideNone
                        wrapMode: Text.WordWrap
                        text: modelData.index + (modelData.practice ? " (practice)" : "") + "  " + modelData.condition
                              + (modelData.summary !== "" ? "  →  " + modelData.summary : "")
                        color: Theme.text
                        font.pixelSize: Theme.fontSmall
                    }
                }
                Item {
                    Layout.fillHeight: true
                }
            }

            // The novice's words for each slider (thesis Table 15: written on
            // sticky notes in the familiarization), kept with the session.
            Card {
                id: tagsCard
                objectName: "sliderTagsCard"
                title: "Slider tags (the participant's words)"
                visible: screen.tagsOpen
                Layout.fillWidth: true
                Layout.fillHeight: true
                // It scrolls, so the field being typed in stays in sight above the keyboard.
                Flickable {
                    id: tagForm
                    Layout.fillWidth: true
                    Layout.preferredHeight: Math.max(0, tagsCard.contentRoom)
                    clip: true
                    contentHeight: tagColumn.implicitHeight
                    function keepInSight() {
                        for (let i = 0; i < tagFields.count; ++i) {
                            const f = tagFields.itemAt(i) as LabeledField;
                            if (!f || !f.typing)
                                continue;
                            const top = f.y, bottom = f.y + f.height;
                            if (top < tagForm.contentY)
                                tagForm.contentY = top;
                            else if (bottom > tagForm.contentY + tagForm.height)
                                tagForm.contentY = Math.min(bottom - tagForm.height, Math.max(0, tagForm.contentHeight - tagForm.height));
                        }
                    }
                    onHeightChanged: keepInSight()
                    ColumnLayout {
                        id: tagColumn
                        width: tagForm.width
                        spacing: Theme.gap
                        GridLayout {
                            Layout.fillWidth: true
                            columns: 2
                            columnSpacing: Theme.gap
                            rowSpacing: Theme.gap / 2
                            Repeater {
                                id: tagFields
                                model: screen.study.protocolSliders
                                LabeledField {
                                    required property var modelData
                                    objectName: "sliderTag." + modelData.parameter
                                    Layout.fillWidth: true
                                    Layout.preferredWidth: 1
                                    label: modelData.label
                                    maximumLength: 200
                                    text: screen.study.sliderTags[modelData.parameter] ?? ""
                                    onTypingChanged: tagForm.keepInSight()
                                }
                            }
                        }
                        RowLayout {
                            Layout.fillWidth: true
                            spacing: Theme.gap
                            ActionButton {
                                objectName: "saveSliderTags"
                                text: "Save"
                                onActivated: {
                                    const words = {};
                                    for (let i = 0; i < tagFields.count; ++i) {
                                        const f = tagFields.itemAt(i) as LabeledField;
                                        if (f)
                                            words[screen.study.protocolSliders[i].parameter] = f.text;
                                    }
                                    screen.study.saveSliderTags(words);
                                }
                            }
                            ActionButton {
                                objectName: "closeSliderTags"
                                text: "Close"
                                onActivated: screen.tagsOpen = false
                            }
                            Item {
                                Layout.fillWidth: true
                            }
                        }
                    }
                }
            }

            // Think-aloud notes and tags, kept with the running trial.
            Card {
                title: "Notes"
                // While the slider tags are typed, the keyboard needs the room.
                visible: !(screen.tagsOpen && screen.keyboardUp)
                Layout.fillWidth: true
                Layout.preferredHeight: implicitHeight
                RowLayout {
                    id: noteRow
                    Layout.fillWidth: true
                    spacing: Theme.gap
                    LabeledField {
                        id: note
                        objectName: "note"
                        Layout.fillWidth: true
                        Layout.minimumWidth: Theme.touch
                        Layout.preferredWidth: 3
                        label: "Note (think-aloud)"
                        maximumLength: 500
                    }
                    LabeledField {
                        id: tags
                        objectName: "tags"
                        Layout.fillWidth: true
                        Layout.minimumWidth: Theme.touch
                        Layout.preferredWidth: 2
                        label: "Tags, comma-separated"
                        maximumLength: 200
                    }
                    ActionButton {
                        id: keep
                        objectName: "keepNote"
                        Layout.alignment: Qt.AlignBottom
                        text: "Keep"
                        enabled: screen.study.state !== "idle" && (note.text.trim() !== "" || tags.text.trim() !== "")
                        onActivated: {
                            screen.study.addNote(note.text, Study.tags(tags.text));
                            note.text = "";
                            tags.text = "";
                        }
                    }
                }
            }
        }
    }
}
