// A tile in the palette: its name over its waveform's shape. Drag it into
// the editor to edit it, or onto a line of the pane to place it; a tap
// picks it (to rename or remove).
import QtQuick

Rectangle {
    id: thumb
    property string name
    property var curve: []
    property bool picked: false
    signal tapped
    // Where the finger is while it drags the tile (scene), and when it lets go.
    signal dragged(point scenePosition, bool done)

    radius: Theme.radius
    color: drag.active ? Theme.line : Theme.raised
    border.color: picked ? Theme.warning : Theme.line
    border.width: picked ? 2 : 1

    CurveCanvas {
        anchors.fill: parent
        anchors.margins: 4
        thumb: thumb.curve
        opacity: 0.55
    }
    Text {
        anchors.fill: parent
        anchors.margins: 4
        text: thumb.name
        color: Theme.text
        wrapMode: Text.WordWrap  // break between words only; Fit shrinks a long word instead
        horizontalAlignment: Text.AlignHCenter
        verticalAlignment: Text.AlignVCenter
        // Long names shrink to fit the tile rather than being cut.
        fontSizeMode: Text.Fit
        minimumPixelSize: 9
        font.pixelSize: Theme.fontSmall
    }
    TapHandler {
        onTapped: thumb.tapped()
    }
    DragHandler {
        id: drag
        target: null
        // The palette's scrolling does not take a tile being dragged out of it.
        grabPermissions: PointerHandler.CanTakeOverFromAnything
        onActiveChanged: if (!drag.active)
            thumb.dragged(drag.centroid.scenePosition, true)
        onCentroidChanged: if (drag.active)
            thumb.dragged(drag.centroid.scenePosition, false)
    }
}
