pragma ComponentBehavior: Bound
// The Haptic Icon Prototyper (thesis ch. 5) in one window (§5.4): the
// waveform editor on top with its exact fields beside it, the tile palette
// and the tile pane below, Play, Undo/Redo, Save/Open above. Tiles move
// between them by dragging: a palette tile into the editor (to edit it) or
// onto a line of the pane (to place it), a selection of the editor into the
// palette (a new tile). Refusals are said in the message bar.
import QtQuick
import QtQuick.Layouts

Item {
    id: screen
    objectName: "prototyperScreen"
    required property DesignSession session
    property bool keyboardUp: false

    // What a finger drags across regions: {kind: "tile", tab, index, name}
    // or {kind: "selection"}; null when nothing.
    property var dragged: null
    property point dragAt

    function dragMove(payload: var, at: point) {
        screen.dragged = payload;
        screen.dragAt = screen.mapFromItem(null, at.x, at.y);
        pane.dropping = payload.kind === "tile";
    }
    function isOver(item: Item, at: point): bool {
        const p = item.mapFromItem(null, at.x, at.y);
        return item.visible && p.x >= 0 && p.y >= 0 && p.x <= item.width && p.y <= item.height;
    }
    // The drop: what lies under the finger takes it.
    function dragDrop(payload: var, at: point) {
        screen.dragged = null;
        if (payload.kind === "tile") {
            const target = pane.dropTarget(at);
            pane.dropping = false;
            if (screen.isOver(editor, at) && screen.session.editTile(payload.tab, payload.index)) {
                // A new waveform: the old one's selection and point mean nothing on it.
                editor.selFrom = NaN;
                editor.selTo = NaN;
                editor.current = -1;
            } else if (target !== null) {
                screen.session.placeTile(target.channel, target.line, payload.tab, payload.index, target.value,
                                         pane.snap(target.channel));
            }
        } else if (payload.kind === "selection" && screen.isOver(palette, at)) {
            screen.session.tileFromSelection(editor.selFrom, editor.selTo, palette.tab);
        }
    }

    ColumnLayout {
        anchors.fill: parent
        anchors.margins: Theme.gap / 2
        spacing: Theme.gap / 2

        PrototyperToolbar {
            id: toolbar
            Layout.fillWidth: true
            session: screen.session
            // With the keyboard up only the part being typed in stays.
            visible: !screen.keyboardUp || toolbar.typing
            onOpenRequested: {
                screen.session.refreshFiles();
                openList.visible = !openList.visible;
            }
        }
        RowLayout {
            id: top
            Layout.fillWidth: true
            Layout.fillHeight: true
            Layout.preferredHeight: 35
            spacing: Theme.gap / 2
            visible: !screen.keyboardUp || controls.typing
            WaveformEditor {
                id: editor
                objectName: "waveformEditor"
                Layout.fillWidth: true
                Layout.fillHeight: true
                session: screen.session
                onSelectionMoved: controls.refreshSelection()
                onPointPicked: controls.refresh()
                onSelectionDragged: (at, done) => done ? screen.dragDrop({ kind: "selection" }, at)
                                                       : screen.dragMove({ kind: "selection" }, at)
            }
            EditorControls {
                id: controls
                Layout.alignment: Qt.AlignTop
                session: screen.session
                editor: editor
            }
        }
        RowLayout {
            Layout.fillWidth: true
            Layout.fillHeight: true
            Layout.preferredHeight: 65
            spacing: Theme.gap / 2
            visible: !screen.keyboardUp || palette.typing || pane.typing
            TilePalette {
                id: palette
                objectName: "tilePalette"
                Layout.preferredWidth: screen.width * 0.36
                Layout.fillHeight: true
                session: screen.session
                onTileDragged: (tab, index, name, at, done) => {
                    const payload = { kind: "tile", tab: tab, index: index, name: name };
                    if (done)
                        screen.dragDrop(payload, at);
                    else
                        screen.dragMove(payload, at);
                }
            }
            TilePane {
                id: pane
                objectName: "tilePane"
                Layout.fillWidth: true
                Layout.fillHeight: true
                session: screen.session
            }
        }
    }

    // The designs in the library folder, to open one.
    Rectangle {
        id: openList
        objectName: "openList"
        visible: false
        z: 5
        x: screen.width - width - Theme.gap
        y: toolbar.y + toolbar.height + Theme.gap
        width: Math.min(screen.width / 2, 420 * Theme.scale)
        height: Math.min(screen.height - y - Theme.gap, files.contentHeight + heading.height + 2 * Theme.gap)
        radius: Theme.radius
        color: Theme.raised
        border.color: Theme.accent
        Text {
            id: heading
            x: Theme.gap
            y: Theme.gap / 2
            width: parent.width - 2 * Theme.gap
            wrapMode: Text.WrapAnywhere
            text: screen.session.designFiles.length > 0 ? "Open a design from " + screen.session.designsDir
                                                        : "No designs in " + screen.session.designsDir + " yet"
            color: Theme.muted
            font.pixelSize: Theme.fontSmall
        }
        ListView {
            id: files
            anchors.fill: parent
            anchors.topMargin: heading.height + Theme.gap
            anchors.margins: Theme.gap / 2
            clip: true
            model: screen.session.designFiles
            delegate: Rectangle {
                id: entry
                required property string modelData
                objectName: "design." + modelData
                width: files.width
                height: Math.round(Theme.touch * 0.7)
                color: tapEntry.pressed ? Theme.line : "transparent"
                Text {
                    anchors.verticalCenter: parent.verticalCenter
                    x: Theme.gap / 2
                    text: entry.modelData
                    color: Theme.text
                    font.pixelSize: Theme.fontBody
                }
                TapHandler {
                    id: tapEntry
                    onTapped: {
                        openList.visible = false;
                        screen.session.open(entry.modelData);
                    }
                }
            }
        }
    }

    // What is being dragged, under the finger.
    Rectangle {
        objectName: "dragGhost"
        visible: screen.dragged !== null
        z: 10
        x: screen.dragAt.x - width / 2
        y: screen.dragAt.y - height / 2
        width: ghostLabel.implicitWidth + Theme.gap
        height: Math.round(Theme.touch * 0.55)
        radius: Theme.radius
        color: "#1d4a6b"
        border.color: Theme.warning
        opacity: 0.9
        Text {
            id: ghostLabel
            anchors.centerIn: parent
            text: screen.dragged === null ? "" : screen.dragged.kind === "tile" ? screen.dragged.name : "new tile"
            color: Theme.text
            font.pixelSize: Theme.fontSmall
        }
    }
}
