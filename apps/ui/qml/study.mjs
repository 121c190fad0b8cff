// What the study screens say and where they draw it: the rating scales'
// words, the affect grid's cells, the dial's angles, the sliders' numbers.

// The words for a scale's two ends, the construct's low and high.
const ends = {
    sam_valence: ["unpleasant", "pleasant"],
    sam_arousal: ["calm", "excited"],
    satisfaction: ["dissatisfied", "satisfied"],
    appropriateness: ["inappropriate", "appropriate"],
    affect_grid: ["low", "high"]
};

// The question put when the protocol gives none.
export function question(scale) {
    switch (scale) {
    case "sam_valence": return "How pleasant did it feel?";
    case "sam_arousal": return "How excited or calm did it make you feel?";
    case "satisfaction": return "How satisfied are you with the match?";
    case "appropriateness": return "How appropriate was the knob for the task?";
    case "affect_grid": return "How did it feel? Tap one square.";
    }
    return "Your rating";
}

// The labels of the lowest and the highest value: which end of the
// construct the scale's minimum stands for is the protocol's min_is.
export function endLabels(scale, minIs) {
    const words = ends[scale] !== undefined ? ends[scale] : ["low", "high"];
    return minIs === "high" ? { min: words[1], max: words[0] } : { min: words[0], max: words[1] };
}

// The values a scale offers, min … max.
export function values(min, max) {
    const out = [];
    for (let v = min; v <= max; ++v)
        out.push(v);
    return out;
}

// The affect grid's cell (column from the left, row from the top) as the
// ratings it stands for: valence grows to the right and arousal upwards
// when the minimum is the construct's low end (both axes reversed for
// min_is "high").
export function gridRating(column, row, min, max, minIs) {
    const n = max - min + 1;
    const valence = minIs === "high" ? max - column : min + column;
    const arousal = minIs === "high" ? min + row : max - row;
    return { valence: Math.max(min, Math.min(max, valence)), arousal: Math.max(min, Math.min(max, arousal)), cells: n };
}

// The dial's drawing angle (degrees clockwise from the top) of a knob angle:
// one revolution of the knob is one turn of the dial.
export function dialAngle(deg) {
    const a = deg % 360;
    return a < 0 ? a + 360 : a;
}

// A slider's value as shown: three significant digits at most, no more
// decimals than the step needs.
export function sliderText(value, unit) {
    if (value === undefined || isNaN(value))
        return "–";
    const digits = Math.abs(value) >= 100 ? 0 : Math.abs(value) >= 10 ? 1 : 2;
    return value.toFixed(digits) + " " + unit;
}

// The session's place: "trial 5 of 112 · block 1, practice · stage all".
export function progress(trial, trials, block, practice, stage) {
    if (!(trial > 0))
        return "–";
    return "trial " + trial + " of " + trials + " · block " + block + (practice ? ", practice" : "")
            + (stage !== "" && stage !== "all" ? " · " + stage : "");
}

// What the experimenter is told the session is doing.
export function stateText(state, message) {
    switch (state) {
    case "idle": return "No session yet";
    case "running": return "Running";
    case "rating": return "The participant is rating";
    case "stopped": return "Stopped" + (message !== "" ? ": " + message : "");
    case "finished": return "Finished: every trial is stored";
    case "error": return "Stopped by an error: " + message;
    }
    return state;
}

// Free-text tags typed as "a, b c": ["a", "b c"].
export function tags(text) {
    return text.split(",").map(t => t.trim()).filter(t => t !== "");
}
