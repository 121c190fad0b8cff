// A capture's fitted Eq. 6 parameters in presentation units with their 95 %
// intervals, and the fit's RMS; a button to fit (again) when given the jobs.
pragma ComponentBehavior: Bound
import QtQuick
import QtQuick.Layouts
import "format.mjs" as Format

Card {
    id: card
    // A library entry (library_reader.hpp's entry_json), or null.
    required property var entry
    // Runs a fit from here; null: the card only shows.
    property JobRunner jobs: null
    title: "Fitted model (Eq. 6), 95 % intervals"
    Text {
        visible: card.entry !== null && card.entry.fit === null
        text: "Not fitted yet."
        color: Theme.muted
        font.pixelSize: Theme.fontBody
    }
    GridLayout {
        visible: card.entry !== null && card.entry.fit !== null
        Layout.fillWidth: true
        columns: 3
        columnSpacing: Theme.gap
        rowSpacing: 2
        Repeater {
            model: card.entry !== null && card.entry.fit !== null ? card.entry.fit.params : []
            delegate: Text {
                required property var modelData
                Layout.fillWidth: true
                text: Format.param(modelData.name, modelData.value, modelData.ci95).label
                color: Theme.muted
                font.pixelSize: Theme.fontBody
                Layout.row: index
                Layout.column: 0
                required property int index
            }
        }
        Repeater {
            model: card.entry !== null && card.entry.fit !== null ? card.entry.fit.params : []
            delegate: Text {
                required property var modelData
                required property int index
                objectName: "param." + modelData.name
                text: Format.param(modelData.name, modelData.value, modelData.ci95).value
                color: Theme.text
                font.pixelSize: Theme.fontBody
                Layout.row: index
                Layout.column: 1
                Layout.alignment: Qt.AlignRight
            }
        }
        Repeater {
            model: card.entry !== null && card.entry.fit !== null ? card.entry.fit.params : []
            delegate: Text {
                required property var modelData
                required property int index
                text: Format.param(modelData.name, modelData.value, modelData.ci95).interval
                color: Theme.muted
                font.pixelSize: Theme.fontSmall
                Layout.row: index
                Layout.column: 2
                Layout.alignment: Qt.AlignRight
            }
        }
    }
    Text {
        objectName: "fitSummary"
        visible: card.entry !== null && card.entry.fit !== null
        text: card.entry !== null && card.entry.fit !== null
              ? "RMS " + Format.torque(card.entry.fit.rmse_Nm) + ", fit " + card.entry.fit.fit_percent.toFixed(1) + " %" : ""
        color: Theme.muted
        font.pixelSize: Theme.fontSmall
    }
    ActionButton {
        objectName: "fitButton"
        visible: card.jobs !== null
        text: card.entry !== null && card.entry.fit !== null ? "Fit again" : "Fit"
        enabled: card.jobs !== null && !card.jobs.running && card.entry !== null
        onActivated: card.jobs.fit(card.entry.capture_id)
    }
}
