// The findings of a capture's latest discrepancy run: each effect named with
// its sentence, or why there is none; a button to look (again) when given the jobs.
pragma ComponentBehavior: Bound
import QtQuick
import QtQuick.Layouts

Card {
    id: findingsCard
    // A library entry (library_reader.hpp's entry_json), or null.
    required property var entry
    // Runs discrepancy discovery from here; null: the card only shows.
    property JobRunner jobs: null
    readonly property var result: entry !== null ? entry.discrepancy : null
    title: "What the model leaves out (discrepancy)"
    Text {
        objectName: "discrepancyNone"
        visible: findingsCard.result === null || findingsCard.result.findings.length === 0
        Layout.fillWidth: true
        wrapMode: Text.WordWrap
        text: findingsCard.result === null ? "Not looked for yet."
              : "No finding: nothing from the effect library cuts the held-out error by 20 %"
                + (findingsCard.result.tentative.length > 0 ? " (tentative: " + findingsCard.result.tentative.map(f => f.effect).join(", ") + ")." : ".")
        color: Theme.muted
        font.pixelSize: Theme.fontBody
    }
    Repeater {
        model: findingsCard.result !== null ? findingsCard.result.findings : []
        delegate: ColumnLayout {
            id: finding
            required property var modelData
            required property int index
            Layout.fillWidth: true
            Text {
                objectName: "finding." + finding.index
                text: finding.modelData.effect + "  (confidence " + finding.modelData.confidence.toFixed(2) + ")"
                color: Theme.warning
                font.pixelSize: Theme.fontBody
                font.bold: true
            }
            Text {
                Layout.fillWidth: true
                wrapMode: Text.WordWrap
                text: finding.modelData.explanation
                color: Theme.text
                font.pixelSize: Theme.fontSmall
            }
        }
    }
    ActionButton {
        objectName: "discrepancyButton"
        text: findingsCard.result !== null ? "Look again" : "Find discrepancies"
        visible: findingsCard.jobs !== null
        enabled: findingsCard.jobs !== null && !findingsCard.jobs.running && findingsCard.entry !== null
        onActivated: findingsCard.jobs.discrepancy(findingsCard.entry.capture_id)
    }
}
