// The knob library: every capture in the store (newest first) with its knob,
// and the chosen one's fitted Eq. 6 parameters with their 95 % intervals and
// the physics discrepancy discovery found missing. Fit and discrepancy run
// from here (as the CLI runs them) and land in the same store.
pragma ComponentBehavior: Bound
import QtQuick
import QtQuick.Layouts
import "format.mjs" as Format

Item {
    id: library
    required property KnobLibrary knobs
    required property JobRunner jobs
    required property DaemonLink link
    signal review(int captureId)
    signal compare(int captureA, int captureB)
    // "Compare with…" tapped: the next knob tapped in the list is B.
    property bool picking: false
    // The capture shown on the right (0: the newest).
    property int captureId: 0
    readonly property var entry: {
        const list = library.knobs.entries;
        for (let i = 0; i < list.length; ++i)
            if (list[i].capture_id === library.captureId)
                return list[i];
        return list.length > 0 ? list[0] : null;
    }
    // The capture whose fit the knob renders now (0: none).
    property int feeling: 0
    readonly property bool feelingThis: entry !== null && feeling === entry.capture_id
    readonly property bool busyHere: jobs.running && entry !== null && jobs.captureId === entry.capture_id

    Component.onCompleted: library.knobs.refresh()

    // "Feel it": the fit's render model (stored with it) loaded into hapticd
    // and rendered; again: back to idle.
    function feel() {
        if (library.feelingThis) {
            library.link.request("set_mode", { mode: "idle" });
            library.feeling = 0;
            return;
        }
        const text = library.knobs.resultFile("fit", library.entry.fit.id, "render_model.json");
        if (text === "") {
            library.link.message("this fit has no render model stored: fit it again", "warning");
            return;
        }
        library.link.request("load_model", JSON.parse(text).params);
        library.link.request("set_mode", { mode: "render" });
        library.feeling = library.entry.capture_id;
    }

    RowLayout {
        anchors.fill: parent
        anchors.margins: Theme.gap
        spacing: Theme.gap

        Rectangle {
            Layout.preferredWidth: parent.width * 0.36
            Layout.fillHeight: true
            color: Theme.surface
            radius: Theme.radius
            border.color: Theme.line

            Text {
                objectName: "libraryEmpty"
                visible: library.knobs.entries.length === 0
                anchors.centerIn: parent
                width: parent.width - 2 * Theme.gap
                wrapMode: Text.WordWrap
                horizontalAlignment: Text.AlignHCenter
                text: library.knobs.loading ? "reading the library…" : "No captures yet. Capture a knob, or import one with knoblab import."
                color: Theme.muted
                font.pixelSize: Theme.fontBody
            }
            ListView {
                id: list
                anchors.fill: parent
                anchors.margins: Theme.gap / 2
                clip: true
                spacing: Theme.gap / 2
                model: library.knobs.entries
                delegate: Rectangle {
                    id: row
                    required property var modelData
                    readonly property bool chosen: library.entry !== null && library.entry.capture_id === row.modelData.capture_id
                    width: ListView.view.width
                    height: Theme.touch * 1.25
                    radius: Theme.radius
                    color: chosen ? Theme.raised : "transparent"
                    border.color: chosen ? Theme.accent : Theme.line
                    Column {
                        anchors.verticalCenter: parent.verticalCenter
                        x: Theme.gap
                        width: parent.width - 2 * Theme.gap
                        Text {
                            width: parent.width
                            elide: Text.ElideNone
                            wrapMode: Text.NoWrap
                            fontSizeMode: Text.HorizontalFit
                            minimumPixelSize: Theme.fontSmall
                            text: (row.modelData.knob !== "" ? row.modelData.knob : "no knob name") + "  ·  capture " + row.modelData.capture_id
                            color: Theme.text
                            font.pixelSize: Theme.fontBody
                            font.bold: true
                        }
                        Text {
                            width: parent.width
                            fontSizeMode: Text.HorizontalFit
                            minimumPixelSize: Math.round(Theme.fontSmall * 0.8)
                            text: row.modelData.started_at.replace("T", " ").replace(/\..*|Z/, "")
                                  + (row.modelData.fit !== null ? "  ·  fitted" : "")
                                  + (row.modelData.discrepancy !== null ? "  ·  " + row.modelData.discrepancy.findings.length + " findings" : "")
                            color: row.modelData.status === "complete" ? Theme.muted : Theme.warning
                            font.pixelSize: Theme.fontSmall
                        }
                    }
                    TapHandler {
                        onTapped: {
                            if (library.picking && !row.chosen) {
                                library.picking = false;
                                library.compare(library.entry.capture_id, row.modelData.capture_id);
                            } else {
                                library.captureId = row.modelData.capture_id;
                            }
                        }
                    }
                }
            }
        }

        Flickable {
            id: detail
            Layout.fillWidth: true
            Layout.fillHeight: true
            clip: true
            contentHeight: body.implicitHeight
            visible: library.entry !== null

            ColumnLayout {
                id: body
                width: detail.width
                spacing: Theme.gap

                Text {
                    objectName: "knobTitle"
                    Layout.fillWidth: true
                    wrapMode: Text.WordWrap
                    text: library.entry !== null ? (library.entry.knob !== "" ? library.entry.knob : "capture " + library.entry.capture_id) : ""
                    color: Theme.text
                    font.pixelSize: Theme.fontTitle
                    font.bold: true
                }
                Text {
                    Layout.fillWidth: true
                    wrapMode: Text.WordWrap
                    text: library.entry !== null ? "capture " + library.entry.capture_id + " · " + library.entry.status + " · "
                                                   + Format.count(library.entry.samples) + " samples at " + Format.rate(library.entry.rate_hz)
                                                   + (library.entry.orientation !== "" ? " · " + Format.orientation(library.entry.orientation) : "")
                                                   + (library.entry.end_reason !== "" ? " · " + library.entry.end_reason : "") : ""
                    color: Theme.muted
                    font.pixelSize: Theme.fontSmall
                }

                FitCard {
                    entry: library.entry
                    jobs: library.jobs
                    Layout.fillWidth: true
                }
                FindingsCard {
                    entry: library.entry
                    jobs: library.jobs
                    Layout.fillWidth: true
                }
                RowLayout {
                    spacing: Theme.gap
                    visible: library.entry !== null && library.entry.fit !== null
                    ActionButton {
                        objectName: "feelButton"
                        text: library.feelingThis ? "Stop rendering" : "Feel it"
                        enabled: library.link.connected
                        onActivated: library.feel()
                    }
                    Text {
                        objectName: "feelState"
                        Layout.fillWidth: true
                        wrapMode: Text.WordWrap
                        text: library.feelingThis && library.link.mode === "render"
                              ? "The knob renders this fit (Eq. 14): turn it." : "Render this fit on the force-feedback knob (Eq. 14)."
                        color: Theme.muted
                        font.pixelSize: Theme.fontSmall
                    }
                }
                Flow {
                    Layout.fillWidth: true
                    spacing: Theme.gap
                    ActionButton {
                        objectName: "reviewButton"
                        visible: library.entry !== null && (library.entry.fit !== null || library.entry.discrepancy !== null)
                        text: "Review the plots"
                        onActivated: library.review(library.entry.capture_id)
                    }
                    ActionButton {
                        objectName: "compareButton"
                        visible: library.knobs.entries.length > 1
                        text: library.picking ? "Cancel compare" : "Compare with…"
                        edge: library.picking ? Theme.warning : Theme.accent
                        onActivated: library.picking = !library.picking
                    }
                }
                Text {
                    objectName: "compareHint"
                    visible: library.picking
                    Layout.fillWidth: true
                    wrapMode: Text.WordWrap
                    text: "Tap another knob in the list to compare it with this one."
                    color: Theme.warning
                    font.pixelSize: Theme.fontBody
                }
                JobProgress {
                    jobs: library.jobs
                    visible: library.busyHere
                    Layout.fillWidth: true
                }
            }
        }
    }
}
