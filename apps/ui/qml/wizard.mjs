// What a press of the camera's capture button means to the capture wizard
// (one-button capture in the field: hapticd reports each press as the
// `capture_button` event; the wizard, which holds the labels, decides).
//
// step: the wizard's step (0 Mounting … 3 Capture, 4 Results); phase: its
// phase (idle | running | failed | fit | discrepancy | done); named: the knob
// has a name. Returns "start" (capture now, at the capture step), "again"
// (a new capture with the same labels, from the results), or a sentence
// saying why the press does nothing.
export function buttonAction(step, phase, named) {
    if (!named)
        return "name the knob first (step 2)";
    if (phase === "running")
        return "a capture is running";
    if (phase === "fit" || phase === "discrepancy")
        return "the last capture is still being analysed";
    if (step === 3)
        return "start";
    if (step === 4)
        return "again";
    return "go on to the capture step first";
}
