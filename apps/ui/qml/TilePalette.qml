pragma ComponentBehavior: Bound
// The tile palette (§5.3.1–5.3.2): tabs the designer names, the templates
// first; a tab's tiles, each dragged into the editor or onto the pane. A
// selection of the editor dropped here becomes a tile of the tab shown.
import QtQuick
import QtQuick.Layouts

Rectangle {
    id: palette
    required property DesignSession session
    property int tab: 0
    property int picked: -1  // the tile picked in this tab, −1: none
    readonly property var tabs: session.palette
    readonly property var tiles: tabs && tab >= 0 && tab < tabs.length ? tabs[tab].tiles : []
    readonly property bool typing: nameField.typing
    signal tileDragged(int tab, int index, string name, point scenePosition, bool done)

    color: Theme.surface
    radius: Theme.radius
    border.color: Theme.line
    onTabsChanged: {
        if (!palette.tabs)
            return;
        if (palette.tab >= palette.tabs.length)
            palette.tab = palette.tabs.length - 1;
        const shown = palette.tab >= 0 ? palette.tabs[palette.tab].tiles.length : 0;
        if (palette.picked >= shown)
            palette.picked = -1;
    }

    ColumnLayout {
        anchors.fill: parent
        anchors.margins: Theme.gap / 2
        spacing: Theme.gap / 3

        Flow {
            Layout.fillWidth: true
            spacing: Theme.gap / 3
            Repeater {
                model: palette.tabs.length
                delegate: SmallButton {
                    required property int index
                    objectName: "tab." + index
                    text: palette.tabs[index]?.name ?? ""  // the tab may be going
                    checked: index === palette.tab
                    onActivated: {
                        palette.tab = index;
                        palette.picked = -1;
                    }
                }
            }
            SmallButton {
                objectName: "addTab"
                text: "+ tab"
                onActivated: if (palette.session.addTab("tab " + (palette.tabs.length + 1))) {
                    palette.tab = palette.tabs.length - 1;
                    palette.picked = -1;
                }
            }
        }
        Flickable {
            id: flick
            Layout.fillWidth: true
            Layout.fillHeight: true
            clip: true
            contentHeight: grid.height
            interactive: contentHeight > height
            Flow {
                id: grid
                width: flick.width
                spacing: Theme.gap / 3
                Repeater {
                    model: palette.tiles.length
                    delegate: TileThumb {
                        required property int index
                        objectName: "tile." + palette.tab + "." + index
                        width: (grid.width - 3 * grid.spacing) / 4
                        height: Math.round(Theme.touch * 0.85)
                        name: palette.tiles[index]?.name ?? ""  // the tile may be going
                        curve: palette.tiles[index]?.thumb ?? []
                        picked: index === palette.picked
                        onTapped: {
                            palette.picked = palette.picked === index ? -1 : index;
                            if (palette.picked >= 0)
                                nameField.text = palette.tiles[index].name;
                        }
                        onDragged: (at, done) => palette.tileDragged(palette.tab, index, palette.tiles[index].name, at, done)
                    }
                }
            }
            Text {
                objectName: "paletteEmpty"
                visible: palette.tiles.length === 0
                width: flick.width
                wrapMode: Text.WordWrap
                text: "Select a stretch of the editor's curve and drag it here to make a tile."
                color: Theme.muted
                font.pixelSize: Theme.fontSmall
            }
        }
        Row {
            spacing: Theme.gap / 3
            SmallField {
                id: nameField
                objectName: "paletteName"
                fieldWidth: 96 * Theme.scale
                onAccepted: palette.picked >= 0 ? renameTile.activated() : renameTab.activated()
            }
            SmallButton {
                id: renameTab
                objectName: "renameTab"
                text: "Name tab"
                onActivated: palette.session.renameTab(palette.tab, nameField.text)
            }
            SmallButton {
                id: renameTile
                objectName: "renameTile"
                text: "Name tile"
                enabled: palette.picked >= 0
                onActivated: palette.session.renameTile(palette.tab, palette.picked, nameField.text)
            }
            SmallButton {
                objectName: "removeTile"
                text: "✕"
                enabled: palette.picked >= 0
                onActivated: if (palette.session.removeTile(palette.tab, palette.picked))
                    palette.picked = -1
            }
        }
    }
}
