pragma ComponentBehavior: Bound
// The waveform editor (thesis §5.3.1, Fig. 71): the curve through its
// control points, as the renderer plays it. A tap on empty space adds a
// point, a tap on a point picks it (its values in the fields beside), a
// long press or a double tap removes it; dragging a point moves it, and
// dragging across empty space selects that stretch. With the mirror line
// on, dragging a selected point scales the whole selection away from the
// line (Fig. 71). Two fingers zoom about where they are (the wheel too).
// Overlays: the device's torque limit, and for velocity and acceleration
// curves the ±20 % band a person can hardly tell from the curve (JND).
import QtQuick
import "design.mjs" as D

Rectangle {
    id: editor
    required property DesignSession session
    // The selection, an x interval in SI (NaN: none).
    property real selFrom: NaN
    property real selTo: NaN
    readonly property bool hasSelection: !isNaN(selFrom) && !isNaN(selTo) && selTo > selFrom
    // The picked point (−1: none).
    property int current: -1
    // The mirror line of Fig. 71: y = mirrorAt (horizontal) or x = mirrorAt.
    property bool mirrorOn: false
    property bool mirrorHorizontal: true
    property real mirrorAt: 0
    // What the view shows, in SI; zoomed until "Whole curve" fits it again.
    property real x0: -1
    property real x1: 1
    property real y0: -0.01
    property real y1: 0.01
    property bool zoomed: false
    readonly property string channel: session.editorChannel
    readonly property var points: session.editorPoints
    readonly property real torqueLimit: session.torqueLimit
    // Friction and inertia changes of 15–20 % are about as small as people
    // feel (JND); the band marks ±20 % around a velocity or mass curve.
    readonly property real jnd: 0.2
    readonly property bool showsJnd: channel === "velocity" || channel === "acceleration"
    readonly property bool showsLimit: channel !== "acceleration"
    // The loop's stability bound (render_stability.hpp): a damping line
    // steeper than ±maxDamping, or a torque rising over θ faster than
    // maxStiffness, is refused by hapticd.
    readonly property real maxDamping: session.maxDamping
    readonly property real maxStiffness: session.maxStiffness
    readonly property bool showsStability: (channel === "velocity" && isFinite(maxDamping))
                                           || (channel === "position" && isFinite(maxStiffness))
    onMaxDampingChanged: canvas.requestPaint()
    // The selection dragged out by its chip: to the screen, which drops it.
    signal selectionDragged(point scenePosition, bool done)

    color: Theme.surface
    radius: Theme.radius
    border.color: Theme.line

    // The curve over the view, as played: sampled again after each edit and
    // each change of view (set here, not bound: a binding would not see an
    // edit that leaves the view as it was).
    property var curve: []
    function resample() {
        editor.curve = editor.session.editorCurve(editor.x0, editor.x1, 240);
        canvas.requestPaint();
    }
    onX1Changed: editor.resample()
    // For the fields beside the editor, which show them.
    signal selectionMoved
    signal pointPicked
    onSelFromChanged: {
        canvas.requestPaint();
        editor.selectionMoved();
    }
    onSelToChanged: {
        canvas.requestPaint();
        editor.selectionMoved();
    }
    onCurrentChanged: editor.pointPicked()

    // The whole curve in view: its points' span, its values with room for the JND band.
    function fit() {
        const pts = editor.points;
        if (pts.length < 2) {
            editor.x0 = -1;
            editor.x1 = 1;
            editor.y0 = -0.01;
            editor.y1 = 0.01;
            editor.zoomed = false;
            return;
        }
        const lo = pts[0].x, hi = pts[pts.length - 1].x;
        const padX = (hi - lo) * 0.04;
        const samples = editor.session.editorCurve(lo, hi, 120);
        // The points and the curve between them (a sample may miss a peak).
        let ylo = 0, yhi = 0;
        for (const p of samples.concat(pts)) {
            ylo = Math.min(ylo, p.y);
            yhi = Math.max(yhi, p.y);
        }
        const grow = editor.showsJnd ? 1 + editor.jnd : 1;
        ylo *= grow;
        yhi *= grow;
        // Room for a point's dot above the highest and below the lowest.
        const padY = Math.max((yhi - ylo) * 0.12, 1e-4);
        editor.x0 = lo - padX;
        editor.x1 = hi + padX;
        editor.y0 = ylo - padY;
        editor.y1 = yhi + padY;
        editor.zoomed = false;
    }
    function px(x: real): real {
        return (x - editor.x0) / (editor.x1 - editor.x0) * plot.width;
    }
    function py(y: real): real {
        return plot.height - (y - editor.y0) / (editor.y1 - editor.y0) * plot.height;
    }
    function sx(p: real): real {
        return editor.x0 + p / plot.width * (editor.x1 - editor.x0);
    }
    function sy(p: real): real {
        return editor.y0 + (plot.height - p) / plot.height * (editor.y1 - editor.y0);
    }
    function inSelection(x: real): bool {
        return editor.hasSelection && x >= editor.selFrom && x <= editor.selTo;
    }
    // The point under a finger at `pos` (plot coordinates), −1 when none.
    function pointAt(pos: point): int {
        let best = -1, bestDistance = Theme.touch * 0.4;
        for (let i = 0; i < editor.points.length; ++i) {
            const d = Math.hypot(editor.px(editor.points[i].x) - pos.x, editor.py(editor.points[i].y) - pos.y);
            if (d <= bestDistance) {
                best = i;
                bestDistance = d;
            }
        }
        return best;
    }
    function zoomAbout(pos: point, factor: real) {
        const cx = editor.sx(pos.x), cy = editor.sy(pos.y);
        editor.x0 = cx - (cx - editor.x0) / factor;
        editor.x1 = cx + (editor.x1 - cx) / factor;
        editor.y0 = cy - (cy - editor.y0) / factor;
        editor.y1 = cy + (editor.y1 - cy) / factor;
        editor.zoomed = true;
    }

    // A drag in progress: "point" (moving one), "scale" (the selection
    // against the mirror line), "select" (across empty space).
    property string dragMode: ""
    property int dragIndex: -1
    property real dragStartX: 0
    property point dragAt
    // The scale factor the drag so far stands for (Fig. 71).
    readonly property real dragFactor: {
        if (editor.dragMode !== "scale" || editor.dragIndex < 0 || editor.dragIndex >= editor.points.length)
            return 1;
        const p = editor.points[editor.dragIndex];
        const from = editor.mirrorHorizontal ? p.y - editor.mirrorAt : p.x - editor.mirrorAt;
        const to = editor.mirrorHorizontal ? editor.sy(editor.dragAt.y) - editor.mirrorAt : editor.sx(editor.dragAt.x) - editor.mirrorAt;
        return Math.abs(from) > 1e-12 ? to / from : 1;
    }
    // Where point i is drawn: where it is, or where the drag is taking it.
    function shown(i: int): point {
        const p = editor.points[i];
        if (editor.dragMode === "point" && i === editor.dragIndex)
            return Qt.point(editor.dragAt.x, editor.dragAt.y);
        if (editor.dragMode === "scale" && editor.inSelection(p.x)) {
            const f = editor.dragFactor;
            return editor.mirrorHorizontal ? Qt.point(editor.px(p.x), editor.py(editor.mirrorAt + f * (p.y - editor.mirrorAt)))
                                           : Qt.point(editor.px(editor.mirrorAt + f * (p.x - editor.mirrorAt)), editor.py(p.y));
        }
        return Qt.point(editor.px(p.x), editor.py(p.y));
    }
    function dragBegin(pos: point) {
        const hit = editor.pointAt(pos);
        editor.dragAt = pos;
        editor.dragIndex = hit;
        if (hit >= 0) {
            editor.current = hit;
            editor.dragMode = editor.mirrorOn && editor.inSelection(editor.points[hit].x) ? "scale" : "point";
        } else {
            editor.dragMode = "select";
            editor.dragStartX = editor.sx(pos.x);
        }
    }
    function dragMove(pos: point) {
        editor.dragAt = pos;
        if (editor.dragMode === "select") {
            const x = editor.sx(pos.x);
            editor.selFrom = Math.min(editor.dragStartX, x);
            editor.selTo = Math.max(editor.dragStartX, x);
        }
    }
    function dragEnd() {
        const mode = editor.dragMode, i = editor.dragIndex, at = editor.dragAt;
        const factor = editor.dragFactor;
        editor.dragMode = "";
        if (mode === "point")
            editor.session.movePoint(i, editor.sx(at.x), editor.sy(at.y));
        else if (mode === "scale")
            editor.session.scaleSelection(editor.selFrom, editor.selTo, editor.mirrorHorizontal, editor.mirrorAt, factor);
    }
    function tapAt(pos: point, count: int) {
        const hit = editor.pointAt(pos);
        if (hit >= 0 && count >= 2) {
            editor.remove(hit);
        } else if (hit >= 0) {
            editor.current = hit;
        } else if (editor.points.length >= 2) {
            const x = editor.sx(pos.x);
            if (editor.session.addPoint(x, editor.sy(pos.y)))
                editor.current = editor.points.findIndex(p => p.x === x);
        }
    }
    function remove(i: int) {
        if (editor.session.removePoint(i))
            editor.current = -1;
    }

    Connections {
        target: editor.session
        function onDesignChanged() {
            if (!editor.zoomed)
                editor.fit();
            editor.resample();
            if (editor.current >= editor.points.length)
                editor.current = -1;
        }
    }
    Component.onCompleted: {
        editor.fit();
        editor.resample();
    }
    onWidthChanged: canvas.requestPaint()
    onX0Changed: editor.resample()
    onY0Changed: canvas.requestPaint()
    onMirrorAtChanged: canvas.requestPaint()
    onMirrorOnChanged: canvas.requestPaint()
    onMirrorHorizontalChanged: canvas.requestPaint()

    // The axes' names and units.
    Text {
        id: axes
        objectName: "editorAxes"
        anchors.left: plot.left
        anchors.top: parent.top
        anchors.topMargin: Theme.gap / 4
        text: D.yName(editor.channel) + " (" + D.yUnit(editor.channel) + ") over " + D.xName(editor.channel) + " ("
              + D.xUnit(editor.channel) + ")"
        color: Theme.muted
        font.pixelSize: Theme.fontSmall
    }
    Item {
        id: plot
        objectName: "editorPlot"
        anchors.fill: parent
        anchors.leftMargin: 58 * Theme.scale
        anchors.rightMargin: Theme.gap
        anchors.topMargin: axes.height + Theme.gap / 2
        anchors.bottomMargin: Theme.fontSmall + Theme.gap
        clip: true
        onHeightChanged: canvas.requestPaint()

        Canvas {
            id: canvas
            anchors.fill: parent
            onPaint: {
                const ctx = getContext("2d");
                ctx.reset();
                const w = width, h = height;
                if (!(w > 0 && h > 0))
                    return;
                // The grid at round values.
                ctx.strokeStyle = Theme.line;
                ctx.lineWidth = 1;
                for (const v of D.ticks(D.xShown(editor.channel, editor.x0), D.xShown(editor.channel, editor.x1), 6)) {
                    const x = editor.px(D.xSi(editor.channel, v));
                    ctx.beginPath();
                    ctx.moveTo(x, 0);
                    ctx.lineTo(x, h);
                    ctx.stroke();
                }
                for (const v of D.ticks(D.yShown(editor.channel, editor.y0), D.yShown(editor.channel, editor.y1), 6)) {
                    const y = editor.py(D.ySi(editor.channel, v));
                    ctx.beginPath();
                    ctx.moveTo(0, y);
                    ctx.lineTo(w, y);
                    ctx.stroke();
                }
                // Zero torque, a little brighter.
                ctx.strokeStyle = Theme.muted;
                ctx.beginPath();
                ctx.moveTo(0, editor.py(0));
                ctx.lineTo(w, editor.py(0));
                ctx.stroke();
                // Beyond the torque limit hapticd clips: shaded.
                if (editor.showsLimit) {
                    ctx.fillStyle = Qt.rgba(1, 0.36, 0.36, 0.18);
                    const top = editor.py(editor.torqueLimit), bottom = editor.py(-editor.torqueLimit);
                    if (top > 0)
                        ctx.fillRect(0, 0, w, top);
                    if (bottom < h)
                        ctx.fillRect(0, bottom, w, h - bottom);
                }
                // The selection.
                if (editor.hasSelection) {
                    ctx.fillStyle = Qt.rgba(0.31, 0.7, 1, 0.16);
                    ctx.fillRect(editor.px(editor.selFrom), 0, editor.px(editor.selTo) - editor.px(editor.selFrom), h);
                }
                const c = editor.curve;
                if (!c || c.length < 2)
                    return;
                // The JND band: ±20 % of the curve.
                if (editor.showsJnd) {
                    ctx.fillStyle = Qt.rgba(0.3, 0.76, 0.54, 0.18);
                    ctx.beginPath();
                    for (let i = 0; i < c.length; ++i)
                        ctx.lineTo(editor.px(c[i].x), editor.py(c[i].y * (1 + editor.jnd)));
                    for (let i = c.length - 1; i >= 0; --i)
                        ctx.lineTo(editor.px(c[i].x), editor.py(c[i].y * (1 - editor.jnd)));
                    ctx.closePath();
                    ctx.fill();
                }
                // The mirror line.
                if (editor.mirrorOn) {
                    ctx.strokeStyle = Theme.warning;
                    ctx.lineWidth = 2;
                    ctx.beginPath();
                    if (editor.mirrorHorizontal) {
                        ctx.moveTo(0, editor.py(editor.mirrorAt));
                        ctx.lineTo(w, editor.py(editor.mirrorAt));
                    } else {
                        ctx.moveTo(editor.px(editor.mirrorAt), 0);
                        ctx.lineTo(editor.px(editor.mirrorAt), h);
                    }
                    ctx.stroke();
                }
                // The stability bound: the steepest damping line the loop renders stably.
                if (editor.showsStability && editor.channel === "velocity") {
                    ctx.strokeStyle = Theme.bad;
                    ctx.lineWidth = 1.5;
                    for (const sign of [1, -1]) {
                        ctx.beginPath();
                        ctx.moveTo(editor.px(editor.x0), editor.py(sign * editor.maxDamping * editor.x0));
                        ctx.lineTo(editor.px(editor.x1), editor.py(sign * editor.maxDamping * editor.x1));
                        ctx.stroke();
                    }
                }
                ctx.strokeStyle = Theme.accent;
                ctx.lineWidth = 2;
                ctx.beginPath();
                for (let i = 0; i < c.length; ++i) {
                    if (i === 0)
                        ctx.moveTo(editor.px(c[i].x), editor.py(c[i].y));
                    else
                        ctx.lineTo(editor.px(c[i].x), editor.py(c[i].y));
                }
                ctx.stroke();
                // Over θ: where the torque rises faster than the loop can render stiffly.
                if (editor.showsStability && editor.channel === "position") {
                    ctx.strokeStyle = Theme.bad;
                    ctx.lineWidth = 4;
                    for (let i = 0; i + 1 < c.length; ++i) {
                        if ((c[i + 1].y - c[i].y) / (c[i + 1].x - c[i].x) <= editor.maxStiffness)
                            continue;
                        ctx.beginPath();
                        ctx.moveTo(editor.px(c[i].x), editor.py(c[i].y));
                        ctx.lineTo(editor.px(c[i + 1].x), editor.py(c[i + 1].y));
                        ctx.stroke();
                    }
                }
            }
        }

        Repeater {
            model: editor.points.length
            delegate: Rectangle {
                id: dot
                required property int index
                objectName: "point." + index
                readonly property point at: editor.shown(index)
                readonly property bool picked: index === editor.current
                width: Math.round(Theme.touch * 0.28)
                height: width
                radius: width / 2
                x: at.x - width / 2
                y: at.y - height / 2
                color: picked ? Theme.warning : editor.inSelection(editor.points[index].x) ? Theme.accent : Theme.text
                border.color: Theme.background
                border.width: 2
            }
        }

        TapHandler {
            id: tap
            onTapped: (eventPoint, button) => editor.tapAt(eventPoint.position, tap.tapCount)
            onLongPressed: {
                const hit = editor.pointAt(tap.point.position);
                if (hit >= 0)
                    editor.remove(hit);
            }
        }
        DragHandler {
            id: drag
            target: null
            minimumPointCount: 1
            maximumPointCount: 1
            onActiveChanged: {
                if (drag.active)
                    editor.dragBegin(drag.centroid.pressPosition);
                else
                    editor.dragEnd();
            }
            onCentroidChanged: if (drag.active)
                editor.dragMove(drag.centroid.position)
        }
        PinchHandler {
            id: pinch
            target: null
            property real lastScale: 1
            onActiveChanged: pinch.lastScale = 1
            onActiveScaleChanged: {
                editor.zoomAbout(pinch.centroid.position, pinch.activeScale / pinch.lastScale);
                pinch.lastScale = pinch.activeScale;
            }
        }
        WheelHandler {
            id: wheel
            onWheel: event => editor.zoomAbout(wheel.point.position, event.angleDelta.y > 0 ? 1.25 : 0.8)
        }

        // Grab the selection here and drop it on the palette: a new tile.
        Rectangle {
            id: chip
            objectName: "selectionChip"
            visible: editor.hasSelection && editor.dragMode !== "select"
            x: Math.max(0, Math.min(plot.width - width, (editor.px(editor.selFrom) + editor.px(editor.selTo) - width) / 2))
            y: Theme.gap / 3
            width: chipLabel.implicitWidth + Theme.gap
            height: Math.round(Theme.touch * 0.55)
            radius: Theme.radius
            color: "#1d4a6b"
            border.color: Theme.accent
            Text {
                id: chipLabel
                anchors.centerIn: parent
                text: "drag to palette ⇣"
                color: Theme.text
                font.pixelSize: Theme.fontSmall
            }
            DragHandler {
                id: chipDrag
                target: null
                onActiveChanged: if (!chipDrag.active)
                    editor.selectionDragged(chipDrag.centroid.scenePosition, true)
                onCentroidChanged: if (chipDrag.active)
                    editor.selectionDragged(chipDrag.centroid.scenePosition, false)
            }
        }

        // What the overlays mean, in the plot's corner (the axes' title
        // takes the line above it).
        Rectangle {
            anchors.right: parent.right
            anchors.top: parent.top
            anchors.margins: 2
            width: legend.implicitWidth + Theme.gap / 2
            height: legend.implicitHeight + 2
            visible: legend.text !== ""
            radius: 4
            color: Qt.rgba(0.08, 0.09, 0.11, 0.8)
            Text {
                id: legend
                objectName: "editorLegend"
                anchors.centerIn: parent
                text: (editor.showsStability ? "red: unstable  " : "") + (editor.showsJnd ? "▒ ±20 % JND  " : "")
                      + (editor.showsLimit ? "▒ limit ±" + D.number(editor.torqueLimit * 1000, 3) + " mN·m" : "")
                color: Theme.muted
                font.pixelSize: Theme.fontSmall
            }
        }

        SmallButton {
            objectName: "zoomReset"
            visible: editor.zoomed
            anchors.right: parent.right
            anchors.bottom: parent.bottom
            anchors.margins: Theme.gap / 3
            text: "Whole curve"
            onActivated: editor.fit()
        }

        Text {
            objectName: "editorEmpty"
            visible: editor.points.length < 2
            anchors.centerIn: parent
            width: parent.width - 2 * Theme.gap
            horizontalAlignment: Text.AlignHCenter
            wrapMode: Text.WordWrap
            text: "Drag a template or a tile here to edit it."
            color: Theme.muted
            font.pixelSize: Theme.fontBody
        }
    }

    // The axes' values at round numbers, in presentation units.
    Repeater {
        model: D.ticks(D.xShown(editor.channel, editor.x0), D.xShown(editor.channel, editor.x1), 6)
        delegate: Text {
            required property real modelData
            x: plot.x + editor.px(D.xSi(editor.channel, modelData)) - width / 2
            y: plot.y + plot.height + 2
            visible: x >= plot.x - width / 2 && x + width <= editor.width
            text: D.number(modelData, 3)
            color: Theme.muted
            font.pixelSize: Theme.fontSmall
        }
    }
    Repeater {
        model: D.ticks(D.yShown(editor.channel, editor.y0), D.yShown(editor.channel, editor.y1), 6)
        delegate: Text {
            required property real modelData
            x: plot.x - width - 4
            y: plot.y + editor.py(D.ySi(editor.channel, modelData)) - height / 2
            visible: y >= plot.y - 2 && y + height <= plot.y + plot.height + 2
            text: D.number(modelData, 3)
            color: Theme.muted
            font.pixelSize: Theme.fontSmall
        }
    }
}
