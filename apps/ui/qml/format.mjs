// How numbers are told on screen: SI inside, these units at the edge.

// A loop rate: "10.0 kHz", "500 Hz"; "–" while unknown.
export function rate(hz) {
    if (!(hz > 0))
        return "–";
    if (hz >= 1000)
        return (hz / 1000).toFixed(hz >= 10000 ? 1 : 2) + " kHz";
    return hz.toFixed(0) + " Hz";
}

// A count with thin-space thousands: 1 234 567.
export function count(n) {
    if (n === undefined || n === null || isNaN(n))
        return "–";
    const s = Math.round(n).toString();
    return s.replace(/\B(?=(\d{3})+(?!\d))/g, "\u2009");
}

// A duration in microseconds: "12 µs", "1.25 ms".
export function micros(us) {
    if (us === undefined || us === null || isNaN(us))
        return "–";
    if (us >= 1000)
        return (us / 1000).toFixed(2) + " ms";
    return us.toFixed(us < 10 ? 1 : 0) + " µs";
}

// How long ago, from seconds: "just now", "5 min ago", "3 h ago", "2 days ago".
export function age(seconds) {
    if (!(seconds >= 0))
        return "–";
    if (seconds < 60)
        return "just now";
    if (seconds < 3600)
        return Math.floor(seconds / 60) + " min ago";
    if (seconds < 86400)
        return Math.floor(seconds / 3600) + " h ago";
    const days = Math.floor(seconds / 86400);
    return days + (days === 1 ? " day ago" : " days ago");
}

// hapticd's fault names (protocol: get_state.faults) as a person reads them.
const faultNames = {
    estop: "E-stop pressed (or its circuit open)",
    amplifier: "amplifier fault",
    amp_comms: "amplifier not answering",
    watchdog: "UI watchdog expired",
    overruns: "loop overruns",
    velocity: "velocity limit",
    commanded: "command not finite or too large",
    io: "sensor or output I/O failed",
    non_finite: "a reading was not finite",
    recording: "a capture could not be stored",
    tracking: "the knob did not follow the sweep"
};

export function fault(name) {
    return faultNames[name] !== undefined ? faultNames[name] : name;
}

// A histogram bin's label from its upper edges (µs): "< 1 µs", "2–4 µs", "> 2 ms".
export function bin(upper, k) {
    if (k === 0)
        return "< " + micros(upper[0]);
    if (k >= upper.length)
        return "> " + micros(upper[upper.length - 1]);
    return micros(upper[k - 1]).replace(/ .*/, "") + "–" + micros(upper[k]);
}

// A fitted parameter of Eq. 6 (SI, as the fit stores it) as the screens show
// it: its name in words, the value and its 95 % interval in presentation
// units (mN·m and friends, detents per revolution, degrees).
const params = {
    M_acc: { label: "inertia M", unit: "mN·m/(rad/s²)", scale: 1000 },
    B_vel_pos: { label: "damping B+", unit: "mN·m/(rad/s)", scale: 1000 },
    B_vel_neg: { label: "damping B−", unit: "mN·m/(rad/s)", scale: 1000 },
    C_vel_pos: { label: "Coulomb C+", unit: "mN·m", scale: 1000 },
    C_vel_neg: { label: "Coulomb C−", unit: "mN·m", scale: 1000 },
    A_pos: { label: "detent amplitude A", unit: "mN·m", scale: 1000 },
    P_pos: { label: "detents per revolution", unit: "", invert: true },
    S_pos: { label: "detent phase S", unit: "°", scale: 180 / Math.PI }
};

function shown(v, digits) {
    const d = digits === undefined ? 3 : digits;
    const a = Math.abs(v);
    if (a !== 0 && (a < 0.01 || a >= 1e5))
        return v.toExponential(d - 1);
    return v.toPrecision(d);
}

export function param(name, value, ci95) {
    const p = params[name];
    const f = p === undefined ? (v => v) : p.invert ? (v => 1 / v) : (v => v * p.scale);
    const unit = p === undefined ? "" : p.unit;
    let interval = "";
    if (ci95 !== undefined && ci95 !== null && ci95.length === 2) {
        const lo = Math.min(f(ci95[0]), f(ci95[1])), hi = Math.max(f(ci95[0]), f(ci95[1]));
        // As many digits as it takes to tell the ends apart (up to 6).
        let digits = 3;
        while (digits < 6 && shown(lo, digits) === shown(hi, digits))
            ++digits;
        interval = shown(lo, digits) + " … " + shown(hi, digits);
    }
    return {
        label: p === undefined ? name : p.label,
        value: shown(f(value)) + (unit !== "" ? " " + unit : ""),
        interval: interval
    };
}

// A torque in N·m as mN·m: "0.164 mN·m".
export function torque(nm) {
    if (nm === undefined || nm === null || isNaN(nm))
        return "–";
    return shown(nm * 1000) + " mN·m";
}

// Where a capture's axis pointed (the store's orientation: JSON such as
// {"tilt_rad": 1.5708}, or words) in words: "axis tilted 90°".
export function orientation(text) {
    if (text === undefined || text === "")
        return "";
    try {
        const o = JSON.parse(text);
        if (o !== null && typeof o === "object" && o.tilt_rad !== undefined)
            return "axis tilted " + Math.round(o.tilt_rad * 180 / Math.PI) + "°";
    } catch (e) {
        // Not JSON: words already.
    }
    return text;
}
