pragma ComponentBehavior: Bound
// Exact numbers for the waveform editor, where a finger is not exact
// enough: the picked point's angle and torque, the selection's ends, the
// mirror line and a scale factor (Fig. 71), in presentation units (°, rad/s
// or s; mN·m) converted to SI here, at the edge.
import QtQuick
import QtQuick.Layouts
import "design.mjs" as D

ColumnLayout {
    id: controls
    required property DesignSession session
    required property WaveformEditor editor
    readonly property string channel: editor.channel
    readonly property bool typing: pointX.typing || pointY.typing || selFrom.typing || selTo.typing || mirrorAt.typing
                                   || factor.typing
    spacing: Theme.gap / 3

    // The fields show the picked point and the selection as they change.
    function refresh() {
        const i = controls.editor.current, pts = controls.editor.points;
        if (i >= 0 && i < pts.length) {
            pointX.text = D.number(D.xShown(controls.channel, pts[i].x), 6);
            pointY.text = D.number(D.yShown(controls.channel, pts[i].y), 6);
        }
    }
    // From the ends themselves: hasSelection, a binding on them, may not
    // have caught up yet when they change.
    function refreshSelection() {
        const a = controls.editor.selFrom, b = controls.editor.selTo;
        if (isNaN(a) && isNaN(b)) {
            selFrom.text = "";
            selTo.text = "";
        } else if (!isNaN(a) && !isNaN(b)) {
            selFrom.text = D.number(D.xShown(controls.channel, a), 6);
            selTo.text = D.number(D.xShown(controls.channel, b), 6);
        }
    }
    // A damping curve's slope at the picked point, in mN·m/(rad/s): the damping it renders there.
    function slope(): string {
        const i = controls.editor.current, pts = controls.editor.points;
        if (controls.channel !== "velocity" || i < 0 || i >= pts.length || pts.length < 2)
            return "";
        const a = pts[Math.max(0, i - 1)], b = pts[Math.min(pts.length - 1, i + 1)];
        return "slope " + D.number((b.y - a.y) / (b.x - a.x) * 1000, 3) + " mN·m/(rad/s)";
    }
    // The mirror line's place: a torque on a horizontal line, an x on a vertical one.
    function applyMirror() {
        if (controls.editor === null)
            return;
        const v = D.parse(mirrorAt.text);
        if (!isNaN(v))
            controls.editor.mirrorAt = controls.editor.mirrorHorizontal ? D.ySi(controls.channel, v)
                                                                         : D.xSi(controls.channel, v);
    }
    Connections {
        target: controls.session
        function onDesignChanged() {
            controls.refresh();
        }
    }

    Text {
        objectName: "pointTitle"
        text: controls.editor.current >= 0 ? "Point " + (controls.editor.current + 1) + "  " + controls.slope()
                                           : "Point: tap one, or type one to add"
        color: Theme.muted
        font.pixelSize: Theme.fontSmall
    }
    Row {
        spacing: Theme.gap / 3
        SmallField {
            id: pointX
            objectName: "pointX"
            unit: D.xUnit(controls.channel)
            fieldWidth: 70 * Theme.scale
            inputMethodHints: Qt.ImhFormattedNumbersOnly
        }
        SmallField {
            id: pointY
            objectName: "pointY"
            unit: D.yUnit(controls.channel)
            fieldWidth: 70 * Theme.scale
            inputMethodHints: Qt.ImhFormattedNumbersOnly
            onAccepted: setPoint.activated()
        }
        SmallButton {
            id: setPoint
            objectName: "setPoint"
            text: "Set"
            enabled: controls.editor.current >= 0
            onActivated: controls.session.movePoint(controls.editor.current, D.xSi(controls.channel, D.parse(pointX.text)),
                                                    D.ySi(controls.channel, D.parse(pointY.text)))
        }
        SmallButton {
            objectName: "addPoint"
            text: "Add"
            onActivated: controls.session.addPoint(D.xSi(controls.channel, D.parse(pointX.text)),
                                                   D.ySi(controls.channel, D.parse(pointY.text)))
        }
        SmallButton {
            objectName: "removePoint"
            text: "✕"
            enabled: controls.editor.current >= 0
            onActivated: controls.editor.remove(controls.editor.current)
        }
    }
    Row {
        spacing: Theme.gap / 3
        SmallField {
            id: selFrom
            objectName: "selectFrom"
            fieldWidth: 62 * Theme.scale
            inputMethodHints: Qt.ImhFormattedNumbersOnly
        }
        SmallField {
            id: selTo
            objectName: "selectTo"
            label: "to"
            unit: D.xUnit(controls.channel)
            fieldWidth: 62 * Theme.scale
            inputMethodHints: Qt.ImhFormattedNumbersOnly
            onAccepted: select.activated()
        }
        SmallButton {
            id: select
            objectName: "select"
            text: "Select"
            onActivated: {
                const a = D.xSi(controls.channel, D.parse(selFrom.text)), b = D.xSi(controls.channel, D.parse(selTo.text));
                if (isNaN(a) || isNaN(b) || !(b > a))
                    return;
                controls.editor.selFrom = a;
                controls.editor.selTo = b;
            }
        }
        SmallButton {
            objectName: "selectAll"
            text: "All"
            enabled: controls.editor.points.length >= 2
            onActivated: {
                const pts = controls.editor.points;
                controls.editor.selFrom = pts[0].x;
                controls.editor.selTo = pts[pts.length - 1].x;
            }
        }
        SmallButton {
            objectName: "selectNone"
            text: "None"
            enabled: controls.editor.hasSelection
            onActivated: {
                controls.editor.selFrom = NaN;
                controls.editor.selTo = NaN;
            }
        }
    }
    Row {
        spacing: Theme.gap / 3
        SmallButton {
            objectName: "mirrorHorizontal"
            text: "— mirror"
            checked: controls.editor.mirrorOn && controls.editor.mirrorHorizontal
            onActivated: {
                controls.editor.mirrorOn = !checked;
                controls.editor.mirrorHorizontal = true;
                controls.applyMirror();
            }
        }
        SmallButton {
            objectName: "mirrorVertical"
            text: "| mirror"
            checked: controls.editor.mirrorOn && !controls.editor.mirrorHorizontal
            onActivated: {
                controls.editor.mirrorOn = !checked;
                controls.editor.mirrorHorizontal = false;
                controls.applyMirror();
            }
        }
        SmallField {
            id: mirrorAt
            objectName: "mirrorAt"
            label: "at"
            text: "0"
            fieldWidth: 50 * Theme.scale
            inputMethodHints: Qt.ImhFormattedNumbersOnly
            onTextChanged: controls.applyMirror()
        }
        SmallField {
            id: factor
            objectName: "scaleFactor"
            label: "×"
            text: "2"
            fieldWidth: 46 * Theme.scale
            inputMethodHints: Qt.ImhFormattedNumbersOnly
            onAccepted: scale.activated()
        }
        SmallButton {
            id: scale
            objectName: "scaleSelection"
            text: "Scale"
            enabled: controls.editor.hasSelection && controls.editor.mirrorOn
            onActivated: controls.session.scaleSelection(controls.editor.selFrom, controls.editor.selTo,
                                                         controls.editor.mirrorHorizontal, controls.editor.mirrorAt,
                                                         D.parse(factor.text))
        }
    }
}
