// The study screens' logic (apps/ui/qml/study.mjs).
import QtQuick
import QtTest
import "../../../apps/ui/qml/study.mjs" as Study

TestCase {
    name: "Study"

    function test_endLabels() {
        // Studies 1–2: low valence at 1; Study 3: the favourable end at 1.
        compare(Study.endLabels("sam_valence", "low"), { min: "unpleasant", max: "pleasant" });
        compare(Study.endLabels("appropriateness", "high"), { min: "appropriate", max: "inappropriate" });
        compare(Study.endLabels("satisfaction", "high").min, "satisfied");
        compare(Study.endLabels("unknown", "low"), { min: "low", max: "high" });
    }

    function test_values() {
        compare(Study.values(1, 9).length, 9);
        compare(Study.values(1, 9)[0], 1);
        compare(Study.values(1, 9)[8], 9);
    }

    function test_gridRating_data() {
        return [
            { tag: "top left, low at min", c: 0, r: 0, minIs: "low", v: 1, a: 9 },
            { tag: "bottom right, low at min", c: 8, r: 8, minIs: "low", v: 9, a: 1 },
            { tag: "centre", c: 4, r: 4, minIs: "low", v: 5, a: 5 },
            { tag: "top left, high at min", c: 0, r: 0, minIs: "high", v: 9, a: 1 }
        ];
    }
    function test_gridRating(data) {
        const g = Study.gridRating(data.c, data.r, 1, 9, data.minIs);
        compare(g.valence, data.v);
        compare(g.arousal, data.a);
        compare(g.cells, 9);
    }

    function test_dialAngle() {
        compare(Study.dialAngle(30), 30);
        compare(Study.dialAngle(-30), 330);
        compare(Study.dialAngle(400), 40);
        compare(Study.dialAngle(-720), 0);
    }

    function test_sliderText() {
        compare(Study.sliderText(0.75, "mN·m"), "0.75 mN·m");
        compare(Study.sliderText(12.34, "mN·m"), "12.3 mN·m");
        compare(Study.sliderText(120, "detents/rev"), "120 detents/rev");
        compare(Study.sliderText(undefined, "mN·m"), "–");
    }

    function test_progress() {
        compare(Study.progress(5, 112, 1, true, "all"), "trial 5 of 112 · block 1, practice");
        compare(Study.progress(20, 32, 2, false, "target"), "trial 20 of 32 · block 2 · target");
        compare(Study.progress(0, 32, 0, false, ""), "–");
    }

    function test_stateText() {
        compare(Study.stateText("error", "hapticd is gone"), "Stopped by an error: hapticd is gone");
        compare(Study.stateText("stopped", ""), "Stopped");
    }

    function test_tags() {
        compare(Study.tags(" hesitant, overshoot ,, detents felt"), ["hesitant", "overshoot", "detents felt"]);
        compare(Study.tags(""), []);
    }
}
