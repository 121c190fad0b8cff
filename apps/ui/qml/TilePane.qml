pragma ComponentBehavior: Bound
// The tile pane (§5.3.2, Figs. 70, 72, 73): four channels — position,
// velocity, acceleration (their tiles lie along θ) and time — each with
// lines of placed tiles. Every active line of every channel that plays is
// summed into what the knob renders; a line's "on" and a channel's "▶" say
// which. Tiles are dropped here from the palette; a picked tile's span can
// be typed; two picked tiles of one channel superimpose into one.
import QtQuick
import QtQuick.Layouts
import "design.mjs" as D

Rectangle {
    id: pane
    required property DesignSession session
    readonly property var channels: session.channels
    // Picked tiles: "channel/line/index".
    property var selected: []
    // A tile is being dragged from the palette: every channel offers a new line.
    property bool dropping: false
    readonly property bool typing: spanFrom.typing || spanTo.typing
    readonly property real headerWidth: 142 * Theme.scale
    readonly property real trackHeight: Math.round(Theme.touch * 0.45)
    // Each line: its on/off toggle, then its track.
    readonly property real toggleWidth: Math.round(trackHeight * 1.4)
    readonly property real trackX: headerWidth + toggleWidth + Theme.gap / 3
    readonly property real trackWidth: Math.max(10, width - trackX - 2 * Theme.gap)

    // The θ axis fits the tiles with room beside them (at least ±90°); time from 0.
    readonly property var thetaRange: {
        let lo = -Math.PI / 2, hi = Math.PI / 2;
        for (let c = 0; c < 3; ++c)
            for (const l of pane.channels[c].lines)
                for (const t of l.tiles) {
                    lo = Math.min(lo, t.from);
                    hi = Math.max(hi, t.to);
                }
        const pad = (hi - lo) * 0.08;
        return [lo - pad, hi + pad];
    }
    readonly property real timeEnd: {
        let end = 2;
        if (pane.channels.length > 3)
            for (const l of pane.channels[3].lines)
                for (const t of l.tiles)
                    end = Math.max(end, t.to * 1.1);
        return end;
    }
    function lo(channel: string): real {
        return channel === "time" ? 0 : pane.thetaRange[0];
    }
    function hi(channel: string): real {
        return channel === "time" ? pane.timeEnd : pane.thetaRange[1];
    }
    // A channel's value (rad or s) ↔ x on a track.
    function toX(channel: string, v: real): real {
        return (v - pane.lo(channel)) / (pane.hi(channel) - pane.lo(channel)) * pane.trackWidth;
    }
    function toValue(channel: string, x: real): real {
        return pane.lo(channel) + x / pane.trackWidth * (pane.hi(channel) - pane.lo(channel));
    }
    // How near (in the channel's unit) an end must land to snap: a fingertip.
    function snap(channel: string): real {
        return Theme.touch * 0.25 / pane.trackWidth * (pane.hi(channel) - pane.lo(channel));
    }
    // Where a channel's value lies on screen: the x a finger aims at.
    function sceneXOf(channel: string, v: real): real {
        return tracks.mapToItem(null, pane.toX(channel, v), 0).x;
    }
    function toggle(key: string) {
        const s = pane.selected.slice();
        const at = s.indexOf(key);
        if (at >= 0)
            s.splice(at, 1);
        else
            s.push(key);
        pane.selected = s.slice(-2);
    }
    function part(key: string, i: int): string {
        return key.split("/")[i];
    }
    // The line under a scene position: {channel, line, value} or null.
    function dropTarget(scene: point): var {
        for (let c = 0; c < channelRepeater.count; ++c) {
            const row = channelRepeater.itemAt(c) as ChannelRow;
            if (row === null)
                continue;
            const hit = row.lineAt(scene);
            if (hit >= 0) {
                const local = tracks.mapFromItem(null, scene.x, scene.y);
                return {
                    channel: row.name,
                    line: hit,
                    value: pane.toValue(row.name, local.x)
                };
            }
        }
        return null;
    }
    onChannelsChanged: pane.selected = []

    color: Theme.surface
    radius: Theme.radius
    border.color: Theme.line

    // The picked tile's span, typed exactly; superimpose; remove.
    readonly property string first: pane.selected.length > 0 ? pane.selected[0] : ""
    readonly property var firstTile: {
        if (pane.first === "")
            return null;
        const c = ["position", "velocity", "acceleration", "time"].indexOf(pane.part(pane.first, 0));
        const l = pane.channels[c].lines[Number(pane.part(pane.first, 1))];
        return l ? l.tiles[Number(pane.part(pane.first, 2))] : null;
    }
    onFirstTileChanged: if (pane.firstTile !== null) {
        const ch = pane.part(pane.first, 0);
        spanFrom.text = D.number(D.spanShown(ch, pane.firstTile.from), 6);
        spanTo.text = D.number(D.spanShown(ch, pane.firstTile.to), 6);
    }

    ColumnLayout {
        anchors.fill: parent
        anchors.margins: Theme.gap / 2
        spacing: Theme.gap / 3

        Row {
            spacing: Theme.gap / 3
            Text {
                objectName: "paneTitle"
                anchors.verticalCenter: parent.verticalCenter
                width: pane.headerWidth - Theme.gap / 2
                text: pane.firstTile !== null ? "span" : "Tile pane"
                color: Theme.muted
                font.pixelSize: Theme.fontSmall
            }
            SmallField {
                id: spanFrom
                objectName: "spanFrom"
                enabled: pane.firstTile !== null
                fieldWidth: 70 * Theme.scale
                inputMethodHints: Qt.ImhFormattedNumbersOnly
            }
            SmallField {
                id: spanTo
                objectName: "spanTo"
                enabled: pane.firstTile !== null
                label: "to"
                unit: D.spanUnit(pane.first !== "" ? pane.part(pane.first, 0) : "position")
                fieldWidth: 70 * Theme.scale
                inputMethodHints: Qt.ImhFormattedNumbersOnly
                onAccepted: setSpan.activated()
            }
            SmallButton {
                id: setSpan
                objectName: "setSpan"
                text: "Set"
                enabled: pane.firstTile !== null
                onActivated: {
                    const ch = pane.part(pane.first, 0);
                    pane.session.resizeTile(ch, Number(pane.part(pane.first, 1)), Number(pane.part(pane.first, 2)),
                                            D.spanSi(ch, D.parse(spanFrom.text)), D.spanSi(ch, D.parse(spanTo.text)));
                }
            }
            SmallButton {
                objectName: "superimpose"
                text: "Superimpose"
                enabled: pane.selected.length === 2
                onActivated: {
                    const a = pane.selected[0], b = pane.selected[1];
                    pane.session.superimpose(pane.part(a, 0), Number(pane.part(a, 1)), Number(pane.part(a, 2)),
                                             Number(pane.part(b, 1)), Number(pane.part(b, 2)));
                }
            }
            SmallButton {
                objectName: "removePlaced"
                text: "✕"
                enabled: pane.firstTile !== null
                onActivated: pane.session.removePlaced(pane.part(pane.first, 0), Number(pane.part(pane.first, 1)),
                                                       Number(pane.part(pane.first, 2)))
            }
        }

        // The θ axis in degrees.
        Item {
            Layout.fillWidth: true
            Layout.preferredHeight: Theme.fontSmall + 4
            Repeater {
                model: D.ticks(D.spanShown("position", pane.lo("position")), D.spanShown("position", pane.hi("position")), 8)
                delegate: Text {
                    required property real modelData
                    x: pane.trackX + pane.toX("position", D.spanSi("position", modelData)) - width / 2
                    visible: x >= pane.trackX - width / 2 && x + width <= pane.width - Theme.gap
                    text: D.number(modelData, 3) + "°"
                    color: Theme.muted
                    font.pixelSize: Theme.fontSmall
                }
            }
        }

        Flickable {
            id: flick
            Layout.fillWidth: true
            Layout.fillHeight: true
            clip: true
            contentHeight: column.height
            interactive: contentHeight > height

            Column {
                id: column
                width: flick.width
                spacing: Theme.gap / 3
                Repeater {
                    id: channelRepeater
                    model: pane.channels.length
                    delegate: ChannelRow {
                        required property int index
                        width: column.width
                        home: pane
                        channel: pane.channels[index]
                    }
                }
            }
            // Where the tracks start: the axis' origin for mapping.
            Item {
                id: tracks
                x: pane.trackX
                y: 0
                width: pane.trackWidth
                height: 1
            }
        }
    }

    component ChannelRow: Row {
        id: row
        required property var home  // the TilePane (its root is a Rectangle to the linter)
        required property var channel
        readonly property string name: channel.name
        readonly property int lineCount: channel.lines.length
        // Its delegates may be made before `home` is given: nothing until it is.
        readonly property bool ready: row.home !== null && row.home !== undefined
        readonly property bool offersNew: row.ready && (row.lineCount === 0 || row.home.dropping)
        // The line whose track is under a scene position (lineCount: the new line), −1: none.
        function lineAt(scene: point): int {
            for (let i = 0; i <= lineRepeater.count; ++i) {
                const lineRow = i < lineRepeater.count ? lineRepeater.itemAt(i) : null;
                const track = lineRow !== null ? lineRow.children[1] : newLine;
                if (track === null || !track.visible)
                    continue;
                const p = track.mapFromItem(null, scene.x, scene.y);
                if (p.x >= 0 && p.x <= track.width && p.y >= 0 && p.y <= track.height)
                    return i;
            }
            return -1;
        }
        spacing: 0

        Row {
            width: row.ready ? row.home.headerWidth : 0
            spacing: Theme.gap / 3
            SmallButton {
                objectName: "play." + row.name
                height: row.ready ? row.home.trackHeight : 0
                text: row.channel.play ? "▶" : "–"
                checked: row.channel.play
                onActivated: row.home.session.setChannelPlay(row.name, !row.channel.play)
            }
            Text {
                anchors.verticalCenter: parent.verticalCenter
                text: row.name === "time" ? "time (s)" : row.name
                color: row.channel.play ? Theme.text : Theme.muted
                font.pixelSize: Theme.fontSmall
            }
        }
        Column {
            spacing: 2
            Repeater {
                id: lineRepeater
                model: row.ready ? row.lineCount : 0
                // A line: on (summed into what plays) or off, and its track.
                delegate: Row {
                    id: lineRow
                    required property int index
                    readonly property var line: row.channel.lines[index] ?? {
                            active: false,
                            tiles: []
                        }
                    spacing: Theme.gap / 3
                    SmallButton {
                        objectName: "active." + row.name + "." + lineRow.index
                        width: row.home.toggleWidth
                        height: row.home.trackHeight
                        text: lineRow.line.active ? "on" : "off"
                        checked: lineRow.line.active
                        onActivated: row.home.session.setLineActive(row.name, lineRow.index, !lineRow.line.active)
                    }
                    PaneLine {
                        objectName: "line." + row.name + "." + lineRow.index
                        pane: row.home
                        channel: row.name
                        lineIndex: lineRow.index
                        tiles: lineRow.line.tiles
                        width: row.home.trackWidth
                        height: row.home.trackHeight
                        opacity: lineRow.line.active ? 1 : 0.45
                    }
                }
            }
            PaneLine {
                id: newLine
                objectName: "line." + row.name + ".new"
                x: row.ready ? row.home.trackX - row.home.headerWidth : 0
                visible: row.offersNew
                pane: row.home
                channel: row.name
                lineIndex: row.lineCount
                isNew: true
                width: row.ready ? row.home.trackWidth : 0
                height: row.ready ? row.home.trackHeight : 0
            }
        }
    }
}
