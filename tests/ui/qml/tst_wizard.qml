// What the capture button means at each step of the wizard (apps/ui/qml/wizard.mjs).
import QtQuick
import QtTest
import "../../../apps/ui/qml/wizard.mjs" as Wizard

TestCase {
    name: "CaptureButton"

    function test_button_data() {
        return [
            { tag: "at the capture step it starts the capture", step: 3, phase: "idle", named: true, action: "start" },
            { tag: "after a failed capture it starts another", step: 3, phase: "failed", named: true, action: "start" },
            { tag: "on the results it captures again", step: 4, phase: "done", named: true, action: "again" },
            { tag: "after a failed analysis it captures again", step: 4, phase: "failed", named: true, action: "again" },
            { tag: "while capturing it does nothing", step: 3, phase: "running", named: true, action: "a capture is running" },
            { tag: "while fitting it does nothing", step: 4, phase: "fit", named: true, action: "the last capture is still being analysed" },
            { tag: "while looking for discrepancies it does nothing", step: 4, phase: "discrepancy", named: true, action: "the last capture is still being analysed" },
            { tag: "an unnamed knob is not captured", step: 3, phase: "idle", named: false, action: "name the knob first (step 2)" },
            { tag: "before the capture step it does nothing", step: 1, phase: "idle", named: true, action: "go on to the capture step first" }
        ];
    }
    function test_button(data) {
        compare(Wizard.buttonAction(data.step, data.phase, data.named), data.action);
    }
}
