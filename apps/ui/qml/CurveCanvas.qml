// A tile's waveform as a thumbnail: `thumb` is [{x, y}] with x in 0…1 and
// y in −1…1 (DesignSession's thumb), drawn edge to edge, zero in the middle.
import QtQuick

Canvas {
    id: canvas
    property var thumb: []
    property color color: Theme.accent

    onThumbChanged: requestPaint()
    onWidthChanged: requestPaint()
    onHeightChanged: requestPaint()
    onPaint: {
        const ctx = getContext("2d");
        ctx.reset();
        ctx.strokeStyle = Theme.line;
        ctx.lineWidth = 1;
        ctx.beginPath();
        ctx.moveTo(0, height / 2);
        ctx.lineTo(width, height / 2);
        ctx.stroke();
        const points = canvas.thumb;
        if (!points || points.length < 2)
            return;
        ctx.strokeStyle = canvas.color;
        ctx.lineWidth = 2;
        ctx.beginPath();
        for (let i = 0; i < points.length; ++i) {
            const px = points[i].x * (width - 2) + 1;
            const py = height / 2 - points[i].y * (height / 2 - 2);
            if (i === 0)
                ctx.moveTo(px, py);
            else
                ctx.lineTo(px, py);
        }
        ctx.stroke();
    }
}
