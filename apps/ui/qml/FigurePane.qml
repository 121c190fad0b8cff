// One report figure for touch: FigureView with pinch (or wheel) to zoom,
// drag to pan, tap for the values at a point, shown under the plot.
pragma ComponentBehavior: Bound
import QtQuick
import QtQuick.Layouts

ColumnLayout {
    id: pane
    // The figure's CSV text ("" shows nothing).
    property alias csv: plot.csv
    property alias panel: plot.panel
    readonly property alias panels: plot.panels
    readonly property alias view: plot
    property string value
    spacing: Theme.gap / 2
    onCsvChanged: pane.value = ""

    function resetView() {
        plot.resetView();
    }

    FigureView {
        id: plot
        objectName: "figureView"
        Layout.fillWidth: true
        Layout.fillHeight: true
        textColor: Theme.muted
        fontPixels: Theme.fontSmall

        property real lastScale: 1
        PinchHandler {
            target: null
            onActiveChanged: plot.lastScale = 1
            onActiveScaleChanged: {
                plot.zoomAt(activeScale / plot.lastScale, centroid.position.x, centroid.position.y);
                plot.lastScale = activeScale;
            }
        }
        DragHandler {
            target: null
            property point last
            onActiveChanged: last = Qt.point(0, 0)
            onTranslationChanged: {
                plot.panBy(translation.x - last.x, translation.y - last.y);
                last = Qt.point(translation.x, translation.y);
            }
        }
        WheelHandler {
            target: null
            onWheel: event => plot.zoomAt(event.angleDelta.y > 0 ? 1.25 : 0.8, point.position.x, point.position.y)
        }
        TapHandler {
            onTapped: (eventPoint, button) => pane.value = plot.valueAt(eventPoint.position.x, eventPoint.position.y)
        }
    }
    Text {
        objectName: "figureValue"
        Layout.fillWidth: true
        elide: Text.ElideNone
        wrapMode: Text.WordWrap
        text: pane.value !== "" ? pane.value : (plot.csv !== "" ? "Tap the plot for the values at a point; pinch or drag to zoom and pan." : "")
        color: pane.value !== "" ? Theme.text : Theme.muted
        font.pixelSize: Theme.fontSmall
    }
}
