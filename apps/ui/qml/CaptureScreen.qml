// The capture wizard: how the camera is mounted (a tripod first calibrates
// gravity at its orientation, Eq. 2), the knob and its gripper, a sensor
// check (Table 4), the capture with the angle and torque live, then the fit
// and the discrepancy run; all of it lands in the knob library.
pragma ComponentBehavior: Bound
import QtQuick
import QtQuick.Layouts
import "format.mjs" as Format
import "wizard.mjs" as Wizard

Item {
    id: wizard
    objectName: "captureWizard"
    required property DaemonLink link
    required property KnobLibrary knobs
    required property JobRunner jobs
    required property TelemetryFeed feed
    signal openLibrary(int captureId)
    // The on-screen keyboard is up (Main's InputPanel).
    property bool keyboardUp: false

    readonly property var steps: ["Mounting", "Knob", "Sensors", "Capture", "Results"]
    property int step: 0
    property string mounting: "lab"
    // The thesis' capture stimulus (Table 3): θ = c·sin φ(t), Eq. 8, over `seconds`.
    readonly property var sweep: ({ a: 0, b: 1.5, c: 1, d: 3 })
    property real seconds: 6
    property int captureId: 0
    property string phase: "idle"  // capture: idle | running | stored | failed; results: fit | discrepancy | done | failed
    property var verification: null  // the spatial calibration's Table 4
    property int gravityRuns: 0
    // Each gravity run turns one revolution each way in this time (the
    // thesis' ~16 s: slow enough that friction and inertia average out).
    property real gravitySeconds: 16
    property string gravityState: "none"  // none | running | accepted | failed
    // knobs.entries named so that the entry follows each re-read of the library.
    readonly property var entry: captureId > 0 && knobs.entries.length >= 0 ? knobs.entry(captureId) : null
    property real startedAt: 0
    property real elapsed: 0

    // A new step takes the focus from the form: the on-screen keyboard goes down.
    onStepChanged: wizard.forceActiveFocus()

    function startCapture() {
        wizard.feed.clear();
        wizard.phase = "running";
        wizard.startedAt = Date.now();
        const args = {
            swept_sine: wizard.sweep,
            seconds: wizard.seconds,
            knob: knobField.text.trim(),
            mounting: wizard.mounting
        };
        if (gripperField.text.trim() !== "")
            args.gripper = gripperField.text.trim();
        if (notesField.text.trim() !== "")
            args.notes = notesField.text.trim();
        wizard.link.request("start_capture", args);
    }
    // The camera's capture button (hapticd's `capture_button` event): at the
    // capture step it starts the capture; on the results, another one with
    // the same labels; elsewhere the message bar says why not.
    function buttonPressed() {
        const action = Wizard.buttonAction(wizard.step, wizard.phase, knobField.text.trim() !== "");
        if (action === "start" || action === "again") {
            wizard.step = 3;
            wizard.startCapture();
        } else {
            wizard.link.message("capture button: " + action, "info");
        }
    }
    function runGravity() {
        wizard.gravityState = "running";
        wizard.link.request("calibrate", { kind: "gravity", gravity_seconds: wizard.gravitySeconds });
    }

    Timer {
        interval: 100
        repeat: true
        running: wizard.phase === "running"
        onTriggered: wizard.elapsed = (Date.now() - wizard.startedAt) / 1000
    }

    Connections {
        target: wizard.link
        function onEvent(name: string, data: var) {
            if (name === "capture_button") {
                wizard.buttonPressed();
            } else if (name === "capture_finished" && data.kind === "stimulus" && wizard.phase === "running") {
                wizard.captureId = data.capture_id;
                wizard.knobs.refresh();
                if (data.complete) {
                    wizard.phase = "fit";
                    wizard.step = 4;
                    wizard.jobs.fit(wizard.captureId);
                } else {
                    wizard.phase = "failed";
                    wizard.link.message("capture " + data.capture_id + " stored incomplete: " + data.end_reason, "warning");
                }
            } else if (name === "calibration_finished") {
                if (data.kind === "spatial")
                    wizard.verification = data;
                if (data.kind === "gravity" && wizard.gravityState === "running") {
                    if (!data.ok) {
                        wizard.gravityState = "failed";
                    } else if (++wizard.gravityRuns < 3) {
                        wizard.link.request("calibrate", { kind: "gravity", gravity_seconds: wizard.gravitySeconds });
                    } else {
                        // Accepted when hapticd says so (it refuses if the runs do not qualify).
                        wizard.link.request("accept_calibration", { kind: "gravity" });
                    }
                }
            }
        }
        function onReplied(token: int, cmd: string, ok: bool, result: var, error: string) {
            if (cmd === "start_capture" && !ok)
                wizard.phase = "failed";
            if (cmd === "calibrate" && !ok && wizard.gravityState === "running")
                wizard.gravityState = "failed";
            if (cmd === "accept_calibration" && wizard.gravityState === "running")
                wizard.gravityState = ok ? "accepted" : "failed";
        }
    }
    Connections {
        target: wizard.jobs
        function onFinished(kind: string, captureId: int, ok: bool, result: var, error: string) {
            if (captureId !== wizard.captureId)
                return;
            if (!ok) {
                wizard.phase = "failed";
                return;
            }
            if (kind === "fit") {
                wizard.phase = "discrepancy";
                wizard.jobs.discrepancy(wizard.captureId);
            } else {
                wizard.phase = "done";
            }
        }
    }

    ColumnLayout {
        anchors.fill: parent
        anchors.margins: Theme.gap
        spacing: Theme.gap

        // Where the wizard is: the steps, the current one lit (not while the
        // keyboard is up: the form needs the room).
        RowLayout {
            Layout.fillWidth: true
            visible: !wizard.keyboardUp
            spacing: Theme.gap / 2
            Repeater {
                model: wizard.steps
                delegate: Rectangle {
                    id: pill
                    required property string modelData
                    required property int index
                    Layout.fillWidth: true
                    Layout.preferredHeight: Theme.touch * 0.6
                    radius: height / 2
                    color: pill.index === wizard.step ? Theme.accent : pill.index < wizard.step ? Theme.raised : Theme.surface
                    border.color: Theme.line
                    Text {
                        anchors.centerIn: parent
                        text: (pill.index + 1) + " " + pill.modelData
                        color: pill.index === wizard.step ? Theme.background : Theme.text
                        font.pixelSize: Theme.fontSmall
                        font.bold: pill.index === wizard.step
                    }
                }
            }
        }

        StackLayout {
            Layout.fillWidth: true
            Layout.fillHeight: true
            // Only the shown step needs room, and the form scrolls.
            Layout.minimumHeight: 0
            currentIndex: wizard.step

            // 1 Mounting
            ColumnLayout {
                spacing: Theme.gap
                Text {
                    text: "Where is the knob?"
                    color: Theme.text
                    font.pixelSize: Theme.fontLarge
                    font.bold: true
                }
                RowLayout {
                    spacing: Theme.gap * 2
                    ChoiceTile {
                        objectName: "mountLab"
                        label: "Lab"
                        detail: "the knob in the chuck, the camera on the lathe bed"
                        chosen: wizard.mounting === "lab"
                        onActivated: wizard.mounting = "lab"
                    }
                    ChoiceTile {
                        objectName: "mountTripod"
                        label: "Tripod"
                        detail: "the camera on a tripod at the knob where it is (a dashboard)"
                        chosen: wizard.mounting === "tripod"
                        onActivated: wizard.mounting = "tripod"
                    }
                }
                RowLayout {
                    visible: wizard.mounting === "tripod"
                    Layout.fillWidth: true
                    spacing: Theme.gap
                    Text {
                        objectName: "gravityState"
                        Layout.fillWidth: true
                        wrapMode: Text.WordWrap
                        text: wizard.gravityState === "accepted" ? "Gravity calibrated at this orientation (3 runs averaged, Eq. 2)."
                              : wizard.gravityState === "running" ? "Calibrating gravity: run " + (wizard.gravityRuns + 1) + " of 3, a revolution each way…"
                              : wizard.gravityState === "failed" ? "The gravity calibration failed; see the message bar."
                              : "At any tilt, the camera's own unbalance adds a torque once per revolution: calibrate it here first (Eq. 2)."
                        color: wizard.gravityState === "failed" ? Theme.bad : Theme.muted
                        font.pixelSize: Theme.fontBody
                    }
                    ActionButton {
                        objectName: "calibrateGravity"
                        text: "Calibrate gravity"
                        enabled: wizard.link.connected && wizard.gravityState !== "running"
                        onActivated: {
                            wizard.gravityRuns = 0;
                            wizard.runGravity();
                        }
                    }
                }
                Item {
                    Layout.fillHeight: true
                }
            }

            // 2 Knob: a form that scrolls, so that the field being typed in
            // stays in sight above the on-screen keyboard.
            Flickable {
                id: form
                clip: true
                contentHeight: fields.implicitHeight
                function keepInSight() {
                    for (const f of [knobField, gripperField, notesField]) {
                        if (!f.typing)
                            continue;
                        const top = f.y, bottom = f.y + f.height;
                        if (top < form.contentY)
                            form.contentY = top;
                        else if (bottom > form.contentY + form.height)
                            form.contentY = Math.min(bottom - form.height, Math.max(0, form.contentHeight - form.height));
                    }
                }
                onHeightChanged: keepInSight()
                ColumnLayout {
                    id: fields
                    width: form.width
                    spacing: Theme.gap
                    LabeledField {
                        id: knobField
                        objectName: "knobName"
                        Layout.fillWidth: true
                        label: "Knob name (the library keeps captures under it)"
                        inputMethodHints: Qt.ImhNoAutoUppercase | Qt.ImhNoPredictiveText
                        placeholder: "e.g. fan-speed, car radio volume"
                        onTypingChanged: form.keepInSight()
                    }
                    LabeledField {
                        id: gripperField
                        objectName: "gripper"
                        Layout.fillWidth: true
                        maximumLength: 128
                        label: "Gripper"
                        placeholder: "e.g. ABS print, VHB tape"
                        onTypingChanged: form.keepInSight()
                    }
                    LabeledField {
                        id: notesField
                        objectName: "notes"
                        Layout.fillWidth: true
                        maximumLength: 512
                        label: "Notes"
                        onTypingChanged: form.keepInSight()
                    }
                }
            }

            // 3 Sensors (Table 4)
            ColumnLayout {
                spacing: Theme.gap
                Text {
                    Layout.fillWidth: true
                    wrapMode: Text.WordWrap
                    text: "Check the sensors: the camera sweeps the knob (Table 3) and compares what it commanded with what it measured (Table 4). Optional."
                    color: Theme.muted
                    font.pixelSize: Theme.fontBody
                }
                ActionButton {
                    objectName: "verifySensors"
                    text: "Check the sensors"
                    enabled: wizard.link.connected && wizard.link.mode !== "calibrate"
                    onActivated: {
                        wizard.verification = null;
                        wizard.link.request("calibrate", { kind: "spatial" });
                    }
                }
                Repeater {
                    model: wizard.verification !== null && wizard.verification.table4 !== undefined
                           ? [["angle", "theta", 180 / Math.PI, "°"], ["speed", "omega", 180 / Math.PI, "°/s"], ["acceleration", "alpha", 180 / Math.PI, "°/s²"]] : []
                    delegate: Text {
                        required property var modelData
                        readonly property var stat: wizard.verification.table4[modelData[1]]
                        objectName: "table4." + modelData[1]
                        visible: stat !== undefined
                        text: stat !== undefined ? modelData[0] + ": commanded − measured " + (stat.mean * modelData[2]).toPrecision(3)
                                                   + " ± " + (stat.sd * modelData[2]).toPrecision(3) + " " + modelData[3] + " (n " + Format.count(stat.n) + ")" : ""
                        color: Theme.text
                        font.pixelSize: Theme.fontBody
                    }
                }
                Item {
                    Layout.fillHeight: true
                }
            }

            // 4 Capture
            ColumnLayout {
                spacing: Theme.gap
                RowLayout {
                    Layout.fillWidth: true
                    spacing: Theme.gap
                    ActionButton {
                        objectName: "startCapture"
                        text: wizard.phase === "running" ? "Capturing…" : "Start capture"
                        enabled: wizard.link.connected && wizard.phase !== "running" && knobField.text.trim() !== ""
                        onActivated: wizard.startCapture()
                    }
                    ActionButton {
                        objectName: "stopCapture"
                        visible: wizard.phase === "running"
                        text: "Stop"
                        edge: Theme.warning
                        onActivated: wizard.link.request("stop_capture")
                    }
                    Text {
                        objectName: "captureState"
                        Layout.fillWidth: true
                        wrapMode: Text.WordWrap
                        text: knobField.text.trim() === "" ? "Name the knob first (step 2)."
                              : wizard.phase === "running" ? "Swept sine (Table 3): " + wizard.elapsed.toFixed(1) + " of " + wizard.seconds + " s"
                              : wizard.phase === "failed" ? "The capture did not complete; see the message bar."
                              : "Swept sine (Table 3), " + wizard.seconds + " s, ±" + (wizard.sweep.c * 180 / Math.PI).toFixed(0) + "° about where the knob is. Tap Start, or press the capture button on the camera."
                        color: wizard.phase === "failed" ? Theme.bad : Theme.muted
                        font.pixelSize: Theme.fontBody
                    }
                }
                TracePlot {
                    objectName: "angleTrace"
                    Layout.fillWidth: true
                    Layout.fillHeight: true
                    feed: wizard.feed
                    channel: "angle"
                    color: Theme.accent
                    textColor: Theme.muted
                    fontPixels: Theme.fontSmall
                }
                TracePlot {
                    objectName: "torqueTrace"
                    Layout.fillWidth: true
                    Layout.fillHeight: true
                    feed: wizard.feed
                    channel: "torque"
                    color: Theme.warning
                    textColor: Theme.muted
                    fontPixels: Theme.fontSmall
                }
            }

            // 5 Results
            Flickable {
                clip: true
                contentHeight: results.implicitHeight
                ColumnLayout {
                    id: results
                    width: parent.width
                    spacing: Theme.gap
                    Text {
                        objectName: "resultState"
                        Layout.fillWidth: true
                        wrapMode: Text.WordWrap
                        text: wizard.phase === "fit" ? "Fitting Eq. 6 to capture " + wizard.captureId + "…"
                              : wizard.phase === "discrepancy" ? "Looking for what the model leaves out…"
                              : wizard.phase === "done" ? "Saved in the library: capture " + wizard.captureId + " of " + knobField.text.trim() + ", its fit and its discrepancy result."
                              : wizard.phase === "failed" ? "Stopped; what finished is in the library." : ""
                        color: wizard.phase === "failed" ? Theme.bad : Theme.text
                        font.pixelSize: Theme.fontBody
                    }
                    JobProgress {
                        jobs: wizard.jobs
                        Layout.fillWidth: true
                    }
                    FitCard {
                        visible: wizard.entry !== null && wizard.entry.fit !== undefined && wizard.entry.fit !== null
                        entry: wizard.entry !== null && wizard.entry.capture_id !== undefined ? wizard.entry : null
                        Layout.fillWidth: true
                    }
                    FindingsCard {
                        visible: wizard.entry !== null && wizard.entry.discrepancy !== undefined && wizard.entry.discrepancy !== null
                        entry: wizard.entry !== null && wizard.entry.capture_id !== undefined ? wizard.entry : null
                        Layout.fillWidth: true
                    }
                    Flow {
                        Layout.fillWidth: true
                        spacing: Theme.gap
                        visible: wizard.phase === "done" || wizard.phase === "failed"
                        ActionButton {
                            objectName: "openLibrary"
                            visible: wizard.phase === "done"
                            text: "Open in the library"
                            onActivated: wizard.openLibrary(wizard.captureId)
                        }
                        ActionButton {
                            objectName: "captureAgain"
                            text: "Capture again"
                            onActivated: wizard.buttonPressed()
                        }
                    }
                    Text {
                        visible: wizard.phase === "done"
                        Layout.fillWidth: true
                        wrapMode: Text.WordWrap
                        text: "The capture button on the camera captures again too, with the same knob, gripper and notes."
                        color: Theme.muted
                        font.pixelSize: Theme.fontSmall
                    }
                }
            }
        }

        // Back and next.
        RowLayout {
            Layout.fillWidth: true
            ActionButton {
                objectName: "back"
                text: "Back"
                visible: wizard.step > 0 && wizard.step < 4
                enabled: wizard.phase !== "running"
                onActivated: wizard.step -= 1
            }
            Item {
                Layout.fillWidth: true
            }
            ActionButton {
                objectName: "next"
                text: wizard.step === 2 && wizard.verification === null ? "Skip" : "Next"
                visible: wizard.step < 3
                enabled: wizard.step !== 1 || knobField.text.trim() !== ""
                onActivated: wizard.step += 1
            }
        }
    }
}
