// The prototyper's presentation units, at the screen's edge only: the design
// is SI inside (DesignSession). Angles in degrees, torques in mN·m, damping
// slopes in mN·m/(rad/s), mass in mN·m/(rad/s²); velocity stays in rad/s
// (a damping slope reads as torque per rad/s) and time in s.
//
// Degrees become radians as v·(π/180), the same double as C++'s
// v * (std::numbers::pi / 180): typed −60° is the design's −60° exactly.
export const kDeg = Math.PI / 180;

// Whether a channel's x (the editor's abscissa, the pane's axis) is an angle.
export function angular(channel) {
    return channel === "position" || channel === "acceleration";
}

export function xShown(channel, x) {
    return angular(channel) ? x / kDeg : x;
}
export function xSi(channel, shown) {
    return angular(channel) ? shown * kDeg : shown;
}
export function xUnit(channel) {
    return angular(channel) ? "°" : channel === "velocity" ? "rad/s" : "s";
}
export function xName(channel) {
    return channel === "velocity" ? "velocity" : channel === "time" ? "time" : "angle";
}

// Torque (N·m) or, drawn for acceleration, mass (kg·m²): both ×1000.
export function yShown(channel, y) {
    return y * 1000;
}
export function ySi(channel, shown) {
    return shown / 1000;
}
export function yUnit(channel) {
    return channel === "acceleration" ? "mN·m/(rad/s²)" : "mN·m";
}
export function yName(channel) {
    return channel === "acceleration" ? "mass" : "torque";
}

// The pane's axis: θ for position, velocity and acceleration tiles, t for time.
export function spanShown(channel, v) {
    return channel === "time" ? v : v / kDeg;
}
export function spanSi(channel, shown) {
    return channel === "time" ? shown : shown * kDeg;
}
export function spanUnit(channel) {
    return channel === "time" ? "s" : "°";
}

// A number as a person types it back: up to `digits` significant digits, no
// trailing zeros, a true minus sign.
export function number(v, digits) {
    if (!isFinite(v))
        return "–";
    let text = Number(v.toPrecision(digits === undefined ? 4 : digits)).toString();
    if (text.indexOf("e") >= 0)
        text = v.toFixed(2);
    return text.replace("-", "−");
}

// A typed number: "−12,5" and "-12.5" both read; NaN when it is not one.
export function parse(text) {
    const t = String(text).trim().replace("−", "-").replace(",", ".");
    if (t === "" || !/^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/.test(t))
        return NaN;
    return Number(t);
}

// Round steps for an axis from lo to hi: about `count` ticks.
export function ticks(lo, hi, count) {
    const span = hi - lo;
    if (!(span > 0))
        return [];
    const raw = span / count;
    const p = Math.pow(10, Math.floor(Math.log10(raw)));
    const step = [1, 2, 5, 10].map(m => m * p).find(s => s >= raw);
    const out = [];
    for (let v = Math.ceil(lo / step) * step; v <= hi + step * 1e-9; v += step)
        out.push(Math.abs(v) < step * 1e-9 ? 0 : v);
    return out;
}
