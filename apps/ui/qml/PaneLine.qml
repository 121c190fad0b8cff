pragma ComponentBehavior: Bound
// One line of a channel in the tile pane: its placed tiles along the
// channel's axis (θ, or t in time). Drag a tile to move it, drag its edge to
// resize it (Fig. 72: a position or time tile's waveform stretches with it),
// tap to pick it (two picked: superimpose, Fig. 73). An end let go near
// another tile's end lands on it exactly (pane_snap.hpp).
import QtQuick

Rectangle {
    id: line
    // The TilePane it is in (var: the pane holds lines, a typed property would be a cycle).
    required property var pane
    required property string channel
    required property int lineIndex
    property var tiles: []
    // The track past the last line: a tile dropped here starts a new line.
    property bool isNew: false

    color: isNew ? "transparent" : Theme.background
    border.color: isNew ? Theme.line : "transparent"
    radius: 4

    Text {
        visible: line.isNew
        anchors.centerIn: parent
        text: "drop a tile here for a new line"
        color: Theme.muted
        font.pixelSize: Theme.fontSmall
    }

    Repeater {
        // Nothing until the line knows its pane (delegates are made first).
        model: line.pane ? line.tiles.length : 0
        delegate: Rectangle {
            id: placed
            required property int index
            // The tile may be going (an undo): its delegate then goes next.
            readonly property var tile: line.tiles[index] ?? {
                    name: "",
                    from: 0,
                    to: 0,
                    thumb: []
                }
            readonly property string key: line.channel + "/" + line.lineIndex + "/" + index
            readonly property bool picked: line.pane.selected.indexOf(key) >= 0
            // While a finger drags the tile or one of its ends: how far (px).
            property real moveBy: 0
            property real fromBy: 0
            property real toBy: 0
            objectName: "placed." + key
            x: line.pane.toX(line.channel, tile.from) + moveBy + fromBy
            width: Math.max(4, line.pane.toX(line.channel, tile.to) - line.pane.toX(line.channel, tile.from) + toBy - fromBy)
            height: line.height
            radius: 4
            color: picked ? "#1d4a6b" : Theme.raised
            border.color: picked ? Theme.warning : Theme.accent
            border.width: picked ? 2 : 1
            clip: true

            CurveCanvas {
                anchors.fill: parent
                anchors.margins: 2
                thumb: placed.tile.thumb
                opacity: 0.6
            }
            TextMetrics {
                id: smallest
                font.pixelSize: 9
                text: placed.tile.name
            }
            Text {
                anchors.fill: parent
                anchors.leftMargin: edgeFrom.width
                anchors.rightMargin: edgeTo.width
                text: placed.tile.name
                color: Theme.text
                horizontalAlignment: Text.AlignHCenter
                verticalAlignment: Text.AlignVCenter
                // One line, shrunk to fit; a tile too short even for the
                // smallest shows no name rather than a cut one.
                visible: smallest.width <= width
                fontSizeMode: Text.HorizontalFit
                minimumPixelSize: 9
                font.pixelSize: Theme.fontSmall
            }
            TapHandler {
                onTapped: line.pane.toggle(placed.key)
            }
            DragHandler {
                id: body
                target: null
                yAxis.enabled: false
                onTranslationChanged: placed.moveBy = body.translation.x
                onActiveChanged: if (!body.active) {
                    const from = line.pane.toValue(line.channel, line.pane.toX(line.channel, placed.tile.from) + placed.moveBy);
                    placed.moveBy = 0;
                    line.pane.session.moveTile(line.channel, line.lineIndex, placed.index, from, line.pane.snap(line.channel));
                }
            }
            // The ends, a finger wide each, to resize.
            Item {
                id: edgeFrom
                objectName: placed.objectName + ".from"
                width: Math.min(Theme.touch * 0.3, placed.width / 3)
                height: parent.height
                Rectangle {
                    anchors.left: parent.left
                    width: 3
                    height: parent.height
                    color: Theme.accent
                }
                DragHandler {
                    id: fromDrag
                    target: null
                    yAxis.enabled: false
                    onTranslationChanged: placed.fromBy = fromDrag.translation.x
                    onActiveChanged: if (!fromDrag.active) {
                        const at = line.pane.toValue(line.channel, line.pane.toX(line.channel, placed.tile.from) + placed.fromBy);
                        placed.fromBy = 0;
                        line.pane.session.resizeTileEnd(line.channel, line.lineIndex, placed.index, "from", at,
                                                        line.pane.snap(line.channel));
                    }
                }
            }
            Item {
                id: edgeTo
                objectName: placed.objectName + ".to"
                anchors.right: parent.right
                width: Math.min(Theme.touch * 0.3, placed.width / 3)
                height: parent.height
                Rectangle {
                    anchors.right: parent.right
                    width: 3
                    height: parent.height
                    color: Theme.accent
                }
                DragHandler {
                    id: toDrag
                    target: null
                    yAxis.enabled: false
                    onTranslationChanged: placed.toBy = toDrag.translation.x
                    onActiveChanged: if (!toDrag.active) {
                        const at = line.pane.toValue(line.channel, line.pane.toX(line.channel, placed.tile.to) + placed.toBy);
                        placed.toBy = 0;
                        line.pane.session.resizeTileEnd(line.channel, line.lineIndex, placed.index, "to", at,
                                                        line.pane.snap(line.channel));
                    }
                }
            }
        }
    }
}
