// The numbers and names the screens show (apps/ui/qml/format.mjs).
import QtQuick
import QtTest
import "../../../apps/ui/qml/format.mjs" as Format

TestCase {
    name: "Format"

    function test_rate_data() {
        return [
            { tag: "10 kHz", hz: 10000, text: "10.0 kHz" },
            { tag: "1 kHz", hz: 1000, text: "1.00 kHz" },
            { tag: "500 Hz", hz: 500, text: "500 Hz" },
            { tag: "unknown", hz: 0, text: "–" },
            { tag: "not a number", hz: NaN, text: "–" }
        ];
    }
    function test_rate(data) {
        compare(Format.rate(data.hz), data.text);
    }

    function test_count() {
        compare(Format.count(1234567), "1\u2009234\u2009567");
        compare(Format.count(999), "999");
        compare(Format.count(undefined), "–");
    }

    function test_micros() {
        compare(Format.micros(3.25), "3.3 µs");
        compare(Format.micros(96), "96 µs");
        compare(Format.micros(1020), "1.02 ms");
        compare(Format.micros(undefined), "–");
    }

    function test_age() {
        compare(Format.age(5), "just now");
        compare(Format.age(300), "5 min ago");
        compare(Format.age(3 * 3600 + 5), "3 h ago");
        compare(Format.age(86400), "1 day ago");
        compare(Format.age(5 * 86400), "5 days ago");
        compare(Format.age(-1), "–");
    }

    function test_fault_names_read_as_words_and_unknown_names_pass_through() {
        compare(Format.fault("estop"), "E-stop pressed (or its circuit open)");
        compare(Format.fault("tracking"), "the knob did not follow the sweep");
        compare(Format.fault("new_fault"), "new_fault");
    }

    function test_histogram_bins_are_labelled_from_their_edges() {
        const upper = [1, 2, 4, 2000];
        compare(Format.bin(upper, 0), "< 1.0 µs");
        compare(Format.bin(upper, 2), "2.0–4.0 µs");
        compare(Format.bin(upper, 4), "> 2.00 ms");
    }

    function test_parameters_are_shown_in_presentation_units_with_their_interval() {
        const a = Format.param("A_pos", 0.011, [0.0109, 0.0111]);
        compare(a.label, "detent amplitude A");
        compare(a.value, "11.0 mN·m");
        compare(a.interval, "10.9 … 11.1");
        const p = Format.param("P_pos", 1 / 12, [1 / 12.5, 1 / 11.5]);
        compare(p.value, "12.0");
        compare(p.interval, "11.5 … 12.5");
        compare(Format.param("S_pos", Math.PI / 2, undefined).value, "90.0 °");
        compare(Format.param("M_acc", 4.79e-5, undefined).value, "0.0479 mN·m/(rad/s²)");
        compare(Format.param("K_new", 2.5, undefined).label, "K_new");
        // An interval too narrow for three digits gets as many as tell its ends apart.
        compare(Format.param("A_pos", 0.011, [0.010995, 0.011014]).interval, "10.99 … 11.01");
    }

    function test_torque_in_millinewton_metres() {
        compare(Format.torque(0.000164), "0.164 mN·m");
        compare(Format.torque(undefined), "–");
    }

    function test_orientation_in_words() {
        compare(Format.orientation('{"tilt_rad": 1.5707963}'), "axis tilted 90°");
        compare(Format.orientation("tripod, dashboard"), "tripod, dashboard");
        compare(Format.orientation(""), "");
    }
}
