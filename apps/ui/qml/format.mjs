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
